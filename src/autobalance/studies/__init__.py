"""Machine-agnostic studies of a System + profile (issue 13/14): statistics and analyses that
take any machine. The seed papers' reproductions live in :mod:`autobalance.papers`."""

__all__: list = []
