"""``python -m rotorpillar.converge CASE.json RESULT.json``: the study's subprocess worker."""

import sys

from .runner import worker


def main(argv: list[str]) -> int:
    if len(argv) != 2:
        print("usage: python -m rotorpillar.converge CASE.json RESULT.json", file=sys.stderr)
        return 2
    worker(argv[0], argv[1])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
