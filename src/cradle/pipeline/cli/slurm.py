"""``cradle slurm``: the workflow built inside one Slurm allocation.

The whole DAG of the targets runs as one Slurm job: ``sbatch`` asks for one node's ``--cpus`` and memory, and
the job runs ``snakemake --cores CPUS TARGET...`` there with Snakemake's local executor, so its rule
instances fork from the warm process (:mod:`cradle.pipeline.warm`) as on a workstation. The other way,
``snakemake --workflow-profile profiles/slurm``, submits the rule instances themselves (grouped); inside a
Slurm job every instance still starts ``srun`` and a Snakemake of its own, and the executor polls ``sacct``:
the place for a sweep bigger than one node, not for the paper's many short jobs (docs/usage.md, "Cluster").

The command waits for the job and prints its log as it grows (``--no-wait``: submit, print the job's id and
log, return); it exits 0 when Slurm says COMPLETED, 1 otherwise. Ctrl-C while waiting cancels the job
(``scancel``), as Snakemake cancels its own Slurm jobs. No Slurm command may hang it: each is given
:data:`TIMEOUT_S`; a missing or hung one, an answer of ``sbatch`` that is not a job id or a state that is none
of Slurm's ends the command in one line, the job cancelled where one may have been submitted. Nothing is
submitted unless the folder holds a Snakefile
and a valid config: the config's errors are one line here, not in a job's log.
"""
from __future__ import annotations

import re
import secrets
import shlex
import shutil
import subprocess
import sys
import time
from pathlib import Path
from typing import TYPE_CHECKING

from cradle.pipeline.cli.common import PROG, CliError, load_config

if TYPE_CHECKING:
    import argparse
    from collections.abc import Sequence

#: where the job's log goes, beside Snakemake's own logs (%j: the job's id)
LOG_PATTERN = ".snakemake/slurm_logs/cradle-%j.log"
#: memory asked per CPU unless --mem-mb says otherwise: a job of the paper's build peaks near 0.3 GB (max RSS),
#: the warm process and Snakemake add about as much again; the rule-instance profile asks as much per job
MEM_PER_CPU_MB = 2000
#: seconds between two looks at the job while waiting
POLL_S = 1.0
#: Slurm states of a job that has ended (squeue stops listing it soon after)
ENDED = {"BOOT_FAIL", "CANCELLED", "COMPLETED", "DEADLINE", "FAILED", "NODE_FAIL", "OUT_OF_MEMORY",
         "PREEMPTED", "TIMEOUT"}
#: every job state Slurm's squeue and sacct print (Slurm 22.05 to 24.11, squeue(1) "JOB STATE CODES"); another
#: answer is not taken for "still running"
STATES = ENDED | {"PENDING", "RUNNING", "CONFIGURING", "COMPLETING", "SUSPENDED", "REQUEUED", "REQUEUE_FED",
                  "REQUEUE_HOLD", "RESIZING", "RESV_DEL_HOLD", "REVOKED", "SIGNALING", "SPECIAL_EXIT", "STAGE_OUT",
                  "STOPPED"}
#: seconds a Slurm command may take before it is taken as hung
TIMEOUT_S = 30.0
#: what a job id is (sbatch --parsable prints "ID" or "ID;CLUSTER")
JOB_ID = re.compile(r"[0-9]{1,19}")


def sbatch_command(targets: Sequence[str], *, cpus: int, mem_mb: int, minutes: int, workdir: str | Path,
                   account: str | None = None, partition: str | None = None, snakemake_args: Sequence[str] = (),
                   python: str | None = None, name: str | None = None) -> list[str]:
    """The ``sbatch`` command line of one allocation running ``snakemake --cores cpus targets...`` in
    ``workdir`` with the interpreter ``python`` (default: this one, hence its packages), its log at
    :data:`LOG_PATTERN` there (appended to, so an older log of the same id is not lost), its job name ``name``
    (default ``cradle-TARGETS``)."""
    inner = [python or sys.executable, "-m", "snakemake", "--cores", str(cpus), *snakemake_args, *targets]
    name = name or f"cradle-{'-'.join(targets) or 'all'}"[:64]
    cmd = ["sbatch", "--parsable", f"--job-name={name}",
           f"--cpus-per-task={cpus}", "--ntasks=1", "--nodes=1", f"--mem={mem_mb}M", f"--time={minutes}",
           f"--chdir={Path(workdir).resolve()}", f"--output={LOG_PATTERN}", "--open-mode=append", "--export=ALL"]
    if account:
        cmd.append(f"--account={account}")
    if partition:
        cmd.append(f"--partition={partition}")
    return [*cmd, "--wrap", "exec " + shlex.join(inner)]


def unique_name(targets: Sequence[str]) -> str:
    """A job name no other job has (``cradle-TARGETS-XXXXXXXX``): the handle that cancels a job whose ``sbatch``
    hung or answered no id."""
    return f"cradle-{'-'.join(targets) or 'all'}"[:55] + f"-{secrets.token_hex(4)}"


class SlurmUnavailable(CliError):
    """A Slurm command missing from PATH or not answering within :data:`TIMEOUT_S`."""


def _run(cmd: list[str], timeout: float | None = None) -> subprocess.CompletedProcess:
    """Run one Slurm command, at most ``timeout`` seconds (:data:`TIMEOUT_S`); missing or hung:
    :class:`SlurmUnavailable`, one line."""
    timeout = TIMEOUT_S if timeout is None else timeout
    try:
        return subprocess.run(cmd, check=False, capture_output=True, text=True, timeout=timeout)
    except FileNotFoundError:
        raise SlurmUnavailable(f"no {cmd[0]} on PATH") from None
    except subprocess.TimeoutExpired:
        raise SlurmUnavailable(f"{cmd[0]} did not answer within {timeout:g} s") from None


def _shown(text: str, most: int = 40) -> str:
    """What a command printed, safe on one line: escapes and control characters shown, long output cut."""
    text = text.strip()
    return ascii(text if len(text) <= most else text[:most] + "...")


def submit(cmd: list[str]) -> str:
    """Submit ``cmd`` (an ``sbatch --parsable`` line); the job's id, a number. A refusal, an answer that is not
    a job id, a missing or hung sbatch: :class:`CliError`, one line."""
    proc = _run(cmd)
    if proc.returncode != 0:
        raise CliError(f"sbatch refused the job: {' '.join(proc.stderr.split()) or 'exit ' + str(proc.returncode)}")
    job_id = proc.stdout.strip().split(";")[0]
    if not JOB_ID.fullmatch(job_id):
        raise CliError(f"sbatch answered {_shown(proc.stdout)}, not a job id (a number)")
    return job_id


def cancel(job_id: str | None, name: str | None = None) -> str:
    """Cancel the job ``job_id`` (or, its id unknown, the job named ``name``); what was done, for a message."""
    target = ["scancel", job_id] if job_id else ["scancel", f"--name={name}"]
    what = f"job {job_id}" if job_id else f"job named {name}"
    try:
        proc = _run(target)
    except SlurmUnavailable as err:
        return f"could not cancel {what}: {err}"
    if proc.returncode != 0:
        return f"could not cancel {what}: scancel: {' '.join(proc.stderr.split()) or 'exit ' + str(proc.returncode)}"
    return f"{what} cancelled (scancel)"


def job_state(job_id: str) -> str | None:
    """The job's state from ``squeue`` (PENDING, RUNNING, ...), or from ``sacct`` once squeue no longer lists
    it; None while neither knows it (accounting may lag a moment behind the end). A missing or hung command:
    :class:`SlurmUnavailable`."""
    proc = _run(["squeue", "-h", "-j", job_id, "-o", "%T"])
    state = proc.stdout.strip() if proc.returncode == 0 else ""
    if state and state not in ENDED:
        return state
    proc = _run(["sacct", "-n", "-X", "-P", "-j", job_id, "-o", "State"])
    lines = [line.split()[0] for line in proc.stdout.splitlines() if line.strip()]
    return lines[0] if lines else (state or None)


class UnknownState(CliError):
    """A state Slurm's commands gave that is none of :data:`STATES`."""


class _Follower:
    """Prints what is appended to the job's log (from ``offset``: what an older log of that name held is not
    printed again)."""

    def __init__(self, path: Path, offset: int = 0) -> None:
        self.path, self.offset = path, offset

    def __call__(self) -> None:
        try:
            with open(self.path, "rb") as fh:
                fh.seek(self.offset)
                data = fh.read()
        except FileNotFoundError:
            return
        if data:
            self.offset += len(data)
            sys.stdout.write(data.decode(errors="replace"))
            sys.stdout.flush()


def wait(job_id: str, log: Path, poll_s: float = POLL_S, follow: bool = True, offset: int = 0) -> str:
    """Wait until the job has ended, printing its log as it grows; its final state (``sacct``). A state that is
    none of Slurm's: :class:`UnknownState`."""
    show = _Follower(log, offset) if follow else (lambda: None)
    unknown_since = None
    while True:
        state = job_state(job_id)
        show()
        if state is not None and state not in STATES:
            raise UnknownState(f"Slurm job {job_id}: state {_shown(state)} is none of Slurm's job states; "
                               f"not followed further (log: {log})")
        if state in ENDED:
            time.sleep(min(poll_s, 0.5))    # the last lines a shared file system shows late
            show()
            return state
        if state is None:
            unknown_since = unknown_since or time.monotonic()
            if time.monotonic() - unknown_since > 120:
                raise CliError(f"Slurm job {job_id}: neither squeue nor sacct knows it (log: {log})")
        time.sleep(poll_s)


def cmd_slurm(args: argparse.Namespace) -> int:
    workdir = Path(args.directory)
    if not (workdir / "Snakefile").is_file():
        raise CliError(f"no Snakefile in {str(workdir)!r}: run from the workflow's folder (or give --directory)")
    if args.mem_mb is None:
        args.mem_mb = MEM_PER_CPU_MB * max(args.cpus, 1)
    for key in ("cpus", "mem_mb", "time"):
        if getattr(args, key) < 1:
            raise CliError(f"--{key.replace('_', '-')} = {getattr(args, key)}: must be >= 1")
    if not args.dry_run:
        missing = [c for c in ("sbatch", "squeue", "sacct", "scancel") if shutil.which(c) is None]
        if "sbatch" in missing:
            raise CliError("no sbatch on PATH: this command submits to Slurm (a local build: snakemake -j2)")
        if missing and not args.no_wait:  # a job submitted that could not be followed or cancelled
            raise CliError(f"no {' and no '.join(missing)} on PATH: needed to follow the job (nothing submitted; "
                           f"--no-wait submits without following)")
    load_config(workdir / args.config)          # a wrong config is one line here, before a job waits in the queue
    extra = list(args.snakemake_args)
    _check_configfiles(workdir, args.config, configfiles(extra))
    if args.config != "config.yaml":
        extra = ["--configfile", args.config, *extra]
    name = unique_name(args.targets)
    cmd = sbatch_command(args.targets, cpus=args.cpus, mem_mb=args.mem_mb, minutes=args.time, workdir=workdir,
                         account=args.account, partition=args.partition, snakemake_args=extra, name=name)
    if args.dry_run:
        print(shlex.join(cmd))
        return 0
    logs = workdir / Path(LOG_PATTERN).parent
    logs.mkdir(parents=True, exist_ok=True)
    # the logs there before submitting: an older job's of the id this one gets is kept (appended to), not reprinted;
    # measured now, as the job may write its first lines before sbatch has answered
    before = {p.name: p.stat().st_size for p in logs.glob("cradle-*.log")}
    try:
        job_id = submit(cmd)
    except CliError as err:  # sbatch hung or answered no id: a job may exist all the same, found by its name
        if isinstance(err, SlurmUnavailable) or str(err).startswith("sbatch answered"):
            raise CliError(f"{err}; {cancel(None, name)}") from None
        raise
    log = log_path(workdir, job_id)
    print(f"{PROG}: Slurm job {job_id} submitted: snakemake --cores {args.cpus} {' '.join(args.targets)} "
          f"in one allocation; log {log}", file=sys.stderr, flush=True)
    if args.no_wait:
        print(job_id)
        return 0
    offset = before.get(log.name, 0)
    t0 = time.monotonic()
    try:
        state = wait(job_id, log, follow=not args.quiet, offset=offset)
    except KeyboardInterrupt:
        cancel(job_id)
        print(f"{PROG}: interrupted: Slurm job {job_id} cancelled (scancel)", file=sys.stderr)
        return 130
    except SlurmUnavailable as err:
        print(f"{PROG}: error: Slurm job {job_id}: {err}; {cancel(job_id)}; log {log}", file=sys.stderr)
        return 1
    except UnknownState as err:
        print(f"{PROG}: error: {err}", file=sys.stderr)
        return 1
    wall = time.monotonic() - t0
    if state != "COMPLETED":
        print(f"{PROG}: error: Slurm job {job_id} ended {state} after {wall:.0f} s; log {log}", file=sys.stderr)
        return 1
    print(f"{PROG}: Slurm job {job_id} COMPLETED in {wall:.1f} s (submission to the end seen here)",
          file=sys.stderr)
    return 0


def log_path(workdir: str | Path, job_id: str) -> Path:
    """The job's log: :data:`LOG_PATTERN` in ``workdir`` with the job's id, which must be a number (no path
    can be made of it)."""
    if not JOB_ID.fullmatch(job_id):
        raise CliError(f"job id {_shown(job_id)}: not a number")
    return Path(workdir) / LOG_PATTERN.replace("%j", job_id)


def add_parser(sub: argparse._SubParsersAction) -> None:
    """The ``slurm`` sub-command's arguments."""
    s = sub.add_parser("slurm", help="build targets inside one Slurm allocation (snakemake --cores CPUS there, "
                                     "jobs forked from the warm process); waits and prints the log")
    s.add_argument("targets", nargs="*", metavar="TARGET",
                   help="Snakemake targets (default: the Snakefile's first, all)")
    s.add_argument("--cpus", type=int, default=2, help="CPUs of the allocation, Snakemake's --cores (default: 2)")
    s.add_argument("--mem-mb", type=int, default=None, dest="mem_mb",
                   help=f"memory of the allocation in MB (default: {MEM_PER_CPU_MB} per CPU; the paper's -j2 build "
                        "peaked at 1.0 GB here)")
    s.add_argument("--time", type=int, default=120, help="time limit in minutes (default: 120)")
    s.add_argument("--account", default=None, help="Slurm account (sbatch --account)")
    s.add_argument("--partition", default=None, help="Slurm partition (sbatch --partition)")
    s.add_argument("--directory", default=".", help="the workflow's folder, with its Snakefile (default: .)")
    s.add_argument("--config", default="config.yaml", help="config file, relative to the folder (default: config.yaml)")
    s.add_argument("--no-wait", action="store_true", dest="no_wait", help="submit, print the job's id, return")
    s.add_argument("--quiet", action="store_true", help="wait without printing the job's log")
    s.add_argument("--dry-run", action="store_true", dest="dry_run", help="print the sbatch command, submit nothing")
    s.set_defaults(func=cmd_slurm, snakemake_args=[])


def configfiles(snakemake_args: Sequence[str]) -> list[str]:
    """The files given to Snakemake by ``--configfile``/``--configfiles`` (each followed by one or more files, or
    ``--configfile=FILE``) among ``snakemake_args``."""
    out, taking = [], False
    for arg in snakemake_args:
        name, eq, value = arg.partition("=")
        if name in ("--configfile", "--configfiles"):
            out += [value] if eq else []
            taking = not eq
        elif taking and not arg.startswith("-"):
            out.append(arg)
        else:
            taking = False
    return out


def _check_configfiles(workdir: Path, config: str, files: list[str]) -> None:
    """Each file Snakemake will be given with ``--configfile`` read by cradle's bounded reader (duplicate keys,
    size, aliases, nesting, encoding: :func:`cradle.pipeline.config.read_yaml`), and the config they make over
    ``config`` validated: one line here, before a job waits in the queue (Snakemake itself reads them with its
    own loader before the Snakefile can)."""
    from cradle.pipeline import config as cc

    if not files:
        return
    merged = cc.read_yaml(workdir / config)
    for name in files:
        path = workdir / name
        if not path.is_file():
            raise CliError(f"no config file {str(path)!r} (given to Snakemake with --configfile)")
        try:
            _update(merged, cc.read_yaml(path))
        except cc.ConfigError as err:   # its line names the file
            raise CliError(str(err).removeprefix("config error: ")) from None
    try:
        cc.validate(merged)
    except cc.ConfigError as err:
        said = "; ".join(line.removeprefix("config error: ") for line in err.errors)
        raise CliError(f"{config} with --configfile {' '.join(files)}: {said}") from None


def _update(base: dict, given: object) -> None:
    """``base`` updated by the mapping ``given`` as Snakemake merges a --configfile: a mapping into a mapping
    key by key, anything else replacing."""
    for key, value in (given.items() if isinstance(given, dict) else ()):
        if isinstance(value, dict) and isinstance(base.get(key), dict):
            _update(base[key], value)
        else:
            base[key] = value


def split_snakemake_args(argv: list[str]) -> tuple[list[str], list[str]]:
    """``cradle slurm TARGET... -- ARGS``: the command's own arguments and Snakemake's (after ``--``)."""
    if "--" in argv:
        i = argv.index("--")
        return argv[:i], argv[i + 1:]
    return argv, []
