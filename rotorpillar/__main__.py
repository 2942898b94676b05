import sys

from .cli import main

# guarded: a worker process started by spawn (the report's renders) imports the
# parent's main module under another name, and must not run the command again
if __name__ == "__main__":
    sys.exit(main())
