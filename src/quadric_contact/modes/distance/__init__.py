"""How far from contact on stacks: distance, penetration depth and the first-contact scale, certified."""
