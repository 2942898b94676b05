"""``python -m rotorpillar.converge --serve``: the study's serving process
(rotorpillar.converge.service); ``python -m rotorpillar.converge CASE.json
RESULT.json``: one run in a fresh process."""

import sys


def main(argv: list[str]) -> int:
    if argv == ["--serve"]:
        from .runner import serve

        return serve()
    if len(argv) != 2:
        print("usage: python -m rotorpillar.converge --serve | CASE.json RESULT.json", file=sys.stderr)
        return 2
    from .runner import worker

    worker(argv[0], argv[1])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
