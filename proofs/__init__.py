"""Machine-checked proofs of the numbered results of Brozos-Vázquez et al.,
*Contact detection between a small ellipsoid and another quadric*, CAGD 98 (2022).

One module per numbered result, named after the paper's numbering; each
defines ``proof = Proof(...)`` (see :mod:`quadric_contact.paper.proving`) and states
in its docstring the claim, what is checked and how.  Run them with
``quadric-contact prove [NAME ...]``; ``quadric-contact prove --report``
regenerates ``REPORT.md``.  Modules whose name starts with ``_`` are shared
helpers, not proofs.
"""
