"""Machine-agnostic studies of a System + profile: statistics and analyses that
take any machine. The seed papers' reproductions live in :mod:`autobalance.papers`."""

__all__: list = []
