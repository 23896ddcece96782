"""The decision: from signs to answers (the one table), the stages in order, the separation certificate."""
