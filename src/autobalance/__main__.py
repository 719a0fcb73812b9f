"""``python -m autobalance ...``: the same as the ``autobalance`` command."""
from .cli import main

if __name__ == "__main__":
    main()
