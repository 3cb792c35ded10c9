"""``cradle slurm``: the sbatch line it builds, its one-line refusals before any submission, and how it follows a
job (log printed as it grows, exit status from Slurm's final state, Ctrl-C cancels), against stand-in
``sbatch``/``squeue``/``sacct``/``scancel`` scripts. The real Slurm: tests/cluster/test_slurm.py."""
from __future__ import annotations

import os
import shlex
import stat
import sys
from pathlib import Path

import pytest
import yaml

from cradle.pipeline.cli import main, slurm as cs

ROOT = Path(__file__).resolve().parents[2]

# Stand-ins for Slurm's commands: sbatch runs $FAKE_JOB (not the wrapped Snakemake) in the background with its
# output in the --output file, records its pid and, at its end, its exit status; squeue says RUNNING while the
# pid lives; sacct says COMPLETED or FAILED from the status; scancel kills it and records the cancellation.
FAKES = {
    "sbatch": r"""#!/bin/sh
state="$FAKE_SLURM"; id=4242; out=""; wrap=""
printf '%s\n' "$@" > "$state/argv"
while [ $# -gt 0 ]; do
  case "$1" in --output=*) out="${1#--output=}";; --chdir=*) cd "${1#--chdir=}";; --wrap) shift; wrap="$1";; esac
  shift
done
out=$(echo "$out" | sed "s/%j/$id/")
( sh -c "$FAKE_JOB" > "$out" 2>&1; echo $? > "$state/status" ) < /dev/null > /dev/null 2>&1 &
echo $! > "$state/pid"
echo "$id"
""",
    "squeue": r"""#!/bin/sh
kill -0 "$(cat "$FAKE_SLURM/pid")" 2>/dev/null && [ ! -e "$FAKE_SLURM/status" ] && echo RUNNING
exit 0
""",
    "sacct": r"""#!/bin/sh
[ -e "$FAKE_SLURM/cancelled" ] && { echo CANCELLED; exit 0; }
[ -e "$FAKE_SLURM/status" ] || exit 0
[ "$(cat "$FAKE_SLURM/status")" = 0 ] && echo COMPLETED || echo FAILED
""",
    "scancel": r"""#!/bin/sh
kill "$(cat "$FAKE_SLURM/pid")" 2>/dev/null; echo "$1" > "$FAKE_SLURM/cancelled"
""",
}


@pytest.fixture
def workflow(tmp_path, monkeypatch):
    """A folder with the project's Snakefile and config, and the stand-ins first on PATH."""
    work = tmp_path / "wf"
    work.mkdir()
    for name in ("Snakefile", "config.yaml"):
        (work / name).write_text((ROOT / name).read_text())
    bin_dir, state = tmp_path / "bin", tmp_path / "state"
    bin_dir.mkdir()
    state.mkdir()
    for name, text in FAKES.items():
        path = bin_dir / name
        path.write_text(text)
        path.chmod(path.stat().st_mode | stat.S_IXUSR)
    monkeypatch.setenv("PATH", f"{bin_dir}{os.pathsep}{os.environ['PATH']}")
    monkeypatch.setenv("FAKE_SLURM", str(state))
    monkeypatch.setattr(cs, "POLL_S", 0.05)
    return work, state


def test_sbatch_line_runs_snakemake_with_the_same_cores_in_one_allocation(tmp_path):
    cmd = cs.sbatch_command(["paper", "plot4-5"], cpus=3, mem_mb=1234, minutes=7, workdir=tmp_path,
                            account="ab1", partition="short", snakemake_args=["--keep-going", "--notemp"])
    assert cmd[0] == "sbatch" and "--parsable" in cmd
    for option in ("--cpus-per-task=3", "--mem=1234M", "--time=7", "--ntasks=1", "--nodes=1", "--account=ab1",
                   "--partition=short", f"--chdir={tmp_path.resolve()}", f"--output={cs.LOG_PATTERN}"):
        assert option in cmd
    wrap = cmd[cmd.index("--wrap") + 1]
    assert wrap.startswith("exec ")
    assert shlex.split(wrap)[1:] == [sys.executable, "-m", "snakemake", "--cores", "3", "--keep-going", "--notemp",
                                     "paper", "plot4-5"]


def test_dry_run_prints_the_line_and_submits_nothing(workflow, capsys):
    work, state = workflow
    assert main(["slurm", "--dry-run", "--directory", str(work), "--cpus", "4", "paper", "--", "-n"]) == 0
    cmd = shlex.split(capsys.readouterr().out.strip())
    assert cmd[0] == "sbatch" and cmd[-2] == "--wrap"
    assert f"--mem={4 * cs.MEM_PER_CPU_MB}M" in cmd                # memory scales with the CPUs unless given
    assert shlex.split(cmd[-1])[-5:] == ["snakemake", "--cores", "4", "-n", "paper"]
    assert not (state / "argv").exists()


def test_without_sbatch_it_says_so(workflow, tmp_path, capsys, monkeypatch):
    work, _ = workflow
    monkeypatch.setenv("PATH", str(tmp_path / "state"))
    assert main(["slurm", "--directory", str(work), "paper"]) == 2
    assert capsys.readouterr().err.strip() == ("cradle: error: no sbatch on PATH: this command submits to Slurm "
                                               "(a local build: snakemake -j2)")


@pytest.mark.parametrize("argv, message", [
    (["--cpus", "0"], "--cpus = 0: must be >= 1"),
    (["--mem-mb", "-5"], "--mem-mb = -5: must be >= 1"),
    (["--time", "0"], "--time = 0: must be >= 1"),
])
def test_bad_resources_are_one_line_before_submitting(workflow, capsys, argv, message):
    work, state = workflow
    assert main(["slurm", "--directory", str(work), *argv, "paper"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"cradle: error: {message}"]
    assert not (state / "argv").exists()


def test_no_snakefile_and_a_wrong_config_are_refused_before_submitting(workflow, tmp_path, capsys):
    work, state = workflow
    assert main(["slurm", "--directory", str(tmp_path / "state"), "paper"]) == 2
    assert "no Snakefile in" in capsys.readouterr().err
    cfg = yaml.safe_load((work / "config.yaml").read_text())
    name = next(iter(cfg["scenes"]))
    cfg["scenes"][name]["N"] = -3
    (work / "config.yaml").write_text(yaml.safe_dump(cfg, sort_keys=False))
    assert main(["slurm", "--directory", str(work), "paper"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and f"scenes.{name}.N" in err[0] and "-3" in err[0], err
    assert not (state / "argv").exists()


def test_a_completed_job_is_followed_and_exits_0(workflow, capsys, monkeypatch):
    work, state = workflow
    monkeypatch.setenv("FAKE_JOB", "echo first line; sleep 0.3; echo 'second line'; exit 0")
    assert main(["slurm", "--directory", str(work), "paper", "--", "--keep-going"]) == 0
    out, err = capsys.readouterr()
    assert out == "first line\nsecond line\n"            # the job's log, whole, in order
    assert "Slurm job 4242 submitted" in err and "Slurm job 4242 COMPLETED" in err
    assert (work / ".snakemake" / "slurm_logs" / "cradle-4242.log").read_text() == out
    argv = (state / "argv").read_text().splitlines()
    assert shlex.split(argv[argv.index("--wrap") + 1])[-2:] == ["--keep-going", "paper"]


def test_a_failed_job_exits_1_naming_its_state_and_log(workflow, capsys, monkeypatch):
    work, _ = workflow
    monkeypatch.setenv("FAKE_JOB", "echo boom; exit 3")
    assert main(["slurm", "--directory", str(work), "--quiet", "paper"]) == 1
    out, err = capsys.readouterr()
    assert out == ""                                      # --quiet: the log is not printed
    last = err.strip().splitlines()[-1]
    assert last.startswith("cradle: error: Slurm job 4242 ended FAILED after") and "cradle-4242.log" in last


def test_no_wait_prints_the_job_id(workflow, capsys, monkeypatch):
    work, state = workflow
    monkeypatch.setenv("FAKE_JOB", "sleep 0.2")
    assert main(["slurm", "--directory", str(work), "--no-wait", "paper"]) == 0
    assert capsys.readouterr().out.strip() == "4242"


def test_interrupt_while_waiting_cancels_the_job(workflow, capsys, monkeypatch):
    work, state = workflow
    monkeypatch.setenv("FAKE_JOB", "sleep 3")

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(cs, "wait", interrupted)
    assert main(["slurm", "--directory", str(work), "paper"]) == 130
    assert "Slurm job 4242 cancelled (scancel)" in capsys.readouterr().err
    assert (state / "cancelled").read_text().strip() == "4242"


# ----------------------------------------------------------------------------- Slurm that is missing, hangs or lies

def _stand_in(state_bin: Path, name: str, text: str) -> None:
    path = state_bin / name
    path.write_text(text)
    path.chmod(path.stat().st_mode | stat.S_IXUSR)


def _last_error(capsys) -> tuple[str, str]:
    out, err = capsys.readouterr()
    lines = [line for line in err.strip().splitlines() if line.startswith("cradle: error:")]
    assert len(lines) == 1 and "Traceback" not in err, err
    return out, lines[0]


def test_no_squeue_on_path_is_refused_before_submitting(workflow, tmp_path, capsys):
    work, state = workflow
    (tmp_path / "bin" / "squeue").unlink()
    assert main(["slurm", "--directory", str(work), "paper"]) == 2
    _, line = _last_error(capsys)
    assert line == ("cradle: error: no squeue on PATH: needed to follow the job (nothing submitted; --no-wait "
                    "submits without following)")
    assert not (state / "argv").exists()


def test_squeue_gone_while_waiting_is_one_line_and_the_job_cancelled(workflow, tmp_path, capsys, monkeypatch):
    work, state = workflow
    monkeypatch.setenv("FAKE_JOB", "sleep 5")
    _stand_in(tmp_path / "bin", "squeue", '#!/bin/sh\nrm -f "$0"\necho RUNNING\n')   # answers once, then is gone
    assert main(["slurm", "--directory", str(work), "paper"]) == 1
    _, line = _last_error(capsys)
    assert line.startswith("cradle: error: Slurm job 4242: no squeue on PATH; job 4242 cancelled (scancel); log ")
    assert (state / "cancelled").read_text().strip() == "4242"


def test_a_hung_sbatch_is_bounded_one_line_and_its_job_cancelled_by_name(workflow, tmp_path, capsys, monkeypatch):
    work, state = workflow
    monkeypatch.setattr(cs, "TIMEOUT_S", 0.5)
    _stand_in(tmp_path / "bin", "sbatch", '#!/bin/sh\necho "$@" > "$FAKE_SLURM/argv"\nexec sleep 30\n')
    assert main(["slurm", "--directory", str(work), "paper"]) == 2
    _, line = _last_error(capsys)
    name = (state / "cancelled").read_text().strip()
    assert name.startswith("--name=cradle-paper-")
    assert line == f"cradle: error: sbatch did not answer within 0.5 s; job named {name[7:]} cancelled (scancel)"


def test_a_hung_squeue_is_bounded_one_line_and_the_job_cancelled(workflow, tmp_path, capsys, monkeypatch):
    work, state = workflow
    monkeypatch.setenv("FAKE_JOB", "sleep 5")
    monkeypatch.setattr(cs, "TIMEOUT_S", 0.5)
    _stand_in(tmp_path / "bin", "squeue", "#!/bin/sh\nexec sleep 30\n")
    assert main(["slurm", "--directory", str(work), "paper"]) == 1
    _, line = _last_error(capsys)
    assert line.startswith("cradle: error: Slurm job 4242: squeue did not answer within 0.5 s; job 4242 cancelled")
    assert (state / "cancelled").read_text().strip() == "4242"


@pytest.mark.parametrize("command", ["squeue", "sacct"])
def test_an_unknown_state_is_one_line_exit_1(workflow, tmp_path, capsys, monkeypatch, command):
    work, _ = workflow
    monkeypatch.setenv("FAKE_JOB", "sleep 5")
    if command == "sacct":   # squeue no longer lists the job, sacct says something Slurm never says
        _stand_in(tmp_path / "bin", "squeue", "#!/bin/sh\nexit 0\n")
    _stand_in(tmp_path / "bin", command, "#!/bin/sh\necho WEIRD_STATE\n")
    assert main(["slurm", "--directory", str(work), "--quiet", "paper"]) == 1
    _, line = _last_error(capsys)
    assert line.startswith("cradle: error: Slurm job 4242: state 'WEIRD_STATE' is none of Slurm's job states; "
                           "not followed further (log: ")


@pytest.mark.parametrize("answer", ["", "\\033[31m4242\\033[0m", "../../etc/passwd", "4242/../../x", "12 13"])
def test_an_sbatch_answer_that_is_not_a_number_is_refused_and_no_log_path_made(workflow, tmp_path, capsys, answer):
    work, state = workflow
    _stand_in(tmp_path / "bin", "sbatch", f'#!/bin/sh\necho "$@" > "$FAKE_SLURM/argv"\nprintf "{answer}\\n"\n')
    assert main(["slurm", "--directory", str(work), "paper"]) == 2
    _, line = _last_error(capsys)
    assert line.startswith("cradle: error: sbatch answered ") and ", not a job id (a number); job named cradle-paper-" \
        in line and "\x1b" not in line
    assert (state / "cancelled").read_text().startswith("--name=cradle-paper-")
    logs = work / ".snakemake" / "slurm_logs"
    assert list(logs.iterdir()) == [] and not (tmp_path / "etc").exists()


def test_the_log_path_is_made_of_a_number_only(tmp_path):
    assert cs.log_path(tmp_path, "4242") == tmp_path / ".snakemake" / "slurm_logs" / "cradle-4242.log"
    for bad in ("", "../x", "42 ", "4e2", "-1"):
        with pytest.raises(cs.CliError, match="not a number"):
            cs.log_path(tmp_path, bad)


def test_an_older_log_of_the_same_id_is_kept_and_not_printed_again(workflow, capsys, monkeypatch):
    work, state = workflow
    log = work / ".snakemake" / "slurm_logs" / "cradle-4242.log"
    log.parent.mkdir(parents=True)
    log.write_text("an earlier cluster's job 4242\n")
    monkeypatch.setenv("FAKE_JOB", "echo new line; exit 0")
    _stand_in_append(work)
    assert main(["slurm", "--directory", str(work), "paper"]) == 0
    assert capsys.readouterr().out == "new line\n"
    assert log.read_text() == "an earlier cluster's job 4242\nnew line\n"
    assert "--open-mode=append" in (state / "argv").read_text().splitlines()


def _stand_in_append(work: Path) -> None:
    """The stand-in sbatch truncates its --output; a real one asked for --open-mode=append appends: do that."""
    path = Path(os.environ["PATH"].split(os.pathsep)[0]) / "sbatch"
    path.write_text(FAKES["sbatch"].replace('> "$out" 2>&1', '>> "$out" 2>&1'))


@pytest.mark.parametrize("args, files", [
    (["--configfile", "a.yaml", "-n"], ["a.yaml"]),
    (["--configfiles", "a.yaml", "b.yaml", "--forceall"], ["a.yaml", "b.yaml"]),
    (["--configfile=a.yaml", "b"], ["a.yaml"]),
    (["-n", "--config", "x=1"], []),
])
def test_the_configfiles_given_to_snakemake_are_found(args, files):
    assert cs.configfiles(args) == files


@pytest.mark.parametrize("text, words", [
    ("budget: {memory_gb: 8, memory_gb: 9}\n", "line 1: key 'memory_gb' given twice in one mapping"),
    (b"budget:\n  memory_gb: 8\nx: \"caf\xe9\"\n", "line 3: byte 0xe9 is not UTF-8 text"),
    ("defaults:\n  alpha: 0.5\n", "config.yaml with --configfile extra.yaml: defaults.alpha = 0.5: must be > 1"),
])
def test_a_configfile_for_snakemake_is_read_by_the_bounded_reader_before_submitting(workflow, capsys, text, words):
    """A file given to Snakemake with --configfile goes through cradle's reader (and the config it makes through
    the validation) before sbatch: one line, nothing submitted."""
    work, state = workflow
    (work / "extra.yaml").write_bytes(text if isinstance(text, bytes) else text.encode())
    assert main(["slurm", "--directory", str(work), "paper", "--", "--configfile", "extra.yaml"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and words in err[0], err
    assert not (state / "argv").exists()
