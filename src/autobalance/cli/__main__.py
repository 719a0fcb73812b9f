"""``python -m autobalance.cli ...``: the same as the ``autobalance`` command (kept for scripts
that ran the former module ``autobalance/cli.py``)."""
from . import main

if __name__ == "__main__":
    main()
