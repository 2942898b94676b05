"""The parser built for one command (rotorpillar.commands.parser.build_parser(only=...),
what `rotorpillar COMMAND ...` parses with) against the parser with every command's
arguments (what `run` parses its stages with): the same namespace for each command's
defaults and for the main job's own stage command lines, and the same top-level help."""

from __future__ import annotations

import contextlib
import io

import pytest

from rotorpillar.commands.parser import COMMANDS, build_parser, command_named
from rotorpillar.commands.run import RUN_STAGES


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_one_commands_parser_reads_its_defaults_as_the_whole_parser(name):
    words = [name, "paper"]
    assert vars(build_parser(only=name).parse_args(words)) == vars(build_parser().parse_args(words))


@pytest.mark.parametrize("stage", RUN_STAGES, ids=lambda st: st.stem)
def test_one_commands_parser_reads_the_main_jobs_stage_lines_as_the_whole_parser(stage):
    words = [*stage.command.split()[:1], "paper", *stage.command.split()[1:], *stage.arguments]
    assert command_named(words) == stage.name
    assert vars(build_parser(only=stage.name).parse_args(words)) == vars(build_parser().parse_args(words))


def test_the_top_level_help_does_not_need_the_commands_arguments():
    def shown(parser) -> str:
        text = io.StringIO()
        with contextlib.redirect_stdout(text), pytest.raises(SystemExit):
            parser.parse_args(["--help"])
        return text.getvalue()

    assert shown(build_parser(only="")) == shown(build_parser())


def test_a_signal_turned_into_another_error_by_a_library_is_still_the_signals_exit(tmp_path, monkeypatch, capsys):
    """SIGTERM while a C extension initialises (petsc4py, imported late since each command
    imports only its own module) comes out of the import as "ImportError: initialization
    failed": the command was stopped, so the exit is 143 with the interrupted line, not 70."""
    import signal

    from rotorpillar import cli

    def stopped_inside_an_import(command, scene, args):
        cli.RECEIVED.append(signal.SIGTERM)
        raise ImportError("initialization failed")

    monkeypatch.setattr(cli, "execute", stopped_inside_an_import)
    assert cli.main(["analyze", "paper", "--out", str(tmp_path)]) == cli.EXIT_TERMINATED
    assert "interrupted" in capsys.readouterr().err

    def a_bug(command, scene, args):
        cli.RECEIVED.clear()
        raise ImportError("a real bug")

    monkeypatch.setattr(cli, "execute", a_bug)
    assert cli.main(["analyze", "paper", "--out", str(tmp_path)]) == 70
