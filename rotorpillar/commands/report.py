"""`rotorpillar report`: render what the other commands computed, then report.html."""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..scene import Scene

import shlex

from ..records import replace
from . import Done, progress


def scene_cli(args) -> str:
    """The scene as the user gave it, with its overrides and --out: what a
    "not computed: run `rotorpillar X ...`" hint must repeat."""
    parts = [str(args.scene)] + [f"--set {shlex.quote(o)}" for o in args.overrides]
    if getattr(args, "out", None) is not None:
        parts.append(f"--out {shlex.quote(str(args.out))}")
    return " ".join(parts)


def add_arguments(parser) -> None:
    parser.add_argument("--max-frames", type=int, default=180, metavar="N", help="frames per animation (default 180)")
    parser.add_argument("--no-animations", action="store_true", help="skip the run-up and earthquake animations")
    parser.add_argument(
        "--mode-pictures",
        type=int,
        default=8,
        metavar="N",
        help="mode-shape pictures of each set of 3D modes (bare and loaded tube) and on its contact sheet (default 8)",
    )
    parser.add_argument(
        "--strict",
        action="store_true",
        help="exit 1 when an input is damaged or a section failed (the page is written all the same)",
    )


#: Frames an animation may have: 2 make a motion, 3600 are two minutes at 30 fps.
MAX_FRAMES_RANGE = (2, 3600)


def checked_frames(args) -> int:
    """``--max-frames``, refused (one line) outside MAX_FRAMES_RANGE; `run` checks it first."""
    return _in_range(args, "--max-frames", 180, MAX_FRAMES_RANGE)


def _in_range(args, flag: str, default: int, bounds: tuple[int, int]) -> int:
    """The value of ``flag`` on ``args`` (``default`` when absent), refused (one line, exit 2)
    outside ``bounds``, both ends allowed."""
    from ..errors import InputError

    value = getattr(args, flag.lstrip("-").replace("-", "_"), default)
    lo, hi = bounds
    if not lo <= value <= hi:
        raise InputError(f"{flag} = {value}: must be {lo} ... {hi}")
    return value


#: Mode-shape pictures a set may have: one at least, 64 at most (a contact sheet of 64 is
#: past reading); no more are drawn than modal lists (8, more where the band holds them).
MODE_PICTURES_RANGE = (1, 64)


def checked_mode_pictures(args) -> int:
    """``--mode-pictures``, refused (one line) outside MODE_PICTURES_RANGE; `run` checks it first."""
    return _in_range(args, "--mode-pictures", 8, MODE_PICTURES_RANGE)


def preflight(scene: Scene, args) -> None:
    """What `report` refuses before any work (`run` calls it for its stage too)."""
    checked_frames(args)
    checked_mode_pictures(args)


def report_command(scene: Scene, args, timings):
    from ..postprocess.report import ReportOptions, build_report, report_text
    from . import is_root_rank, out_dir

    frames, modes = checked_frames(args), checked_mode_pictures(args)
    if not is_root_rank():
        from ..postprocess.report import ReportResult

        return Done(ReportResult(report=None), "")
    options = ReportOptions(animations=not getattr(args, "no_animations", False), max_frames=frames, modes=modes)
    progress(f"report: rendering into {out_dir(scene, args)}")
    from ..verdict.summary import write_summary

    failed = None
    with timings("summary"):
        try:
            path = write_summary(scene, out_dir(scene, args))
            written = None if path is None else str(path)
        except (KeyError, TypeError, ValueError, AttributeError) as exc:  # a damaged input: said, not fatal
            written, failed = None, f"{type(exc).__name__}: {exc}"
            progress(f"report: summary.json not written: {failed}")
    result = build_report(scene, out_dir(scene, args), scene_cli(args), options, timings)
    failures = {**result.failures, **({"summary.json": failed} if failed else {})}
    result = replace(result, summary=written, failures=failures)
    status = 1 if getattr(args, "strict", False) and (result.failures or result.damaged) else 0
    if status:  # why --strict fails, on stderr (stdout may carry --json): each input or step at fault
        # (a damaged input is among the failures too, as "input <file>")
        for key, why in result.failures.items():
            print(f"rotorpillar report: --strict: {key}: {why}", file=sys.stderr)
    return Done(result, report_text(result), status)
