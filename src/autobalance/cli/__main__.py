"""``python -m autobalance.cli ...``: the same as the ``autobalance`` command."""
from . import main

if __name__ == "__main__":
    main()
