"""Studies (paper §4 and appendices): a study file expands into jobs (surface pair × material × contact setting ×
load), each a sliding run stored as one job file in a result folder; finished jobs are skipped when a
study is run again, so an interrupted study resumes where it stopped. The folder layout is that of
``wearsim study run``, so the CLI and Python can take turns on the same folder.

Run locally (threads of this machine), or on a Dask cluster by passing a
``dask.distributed.Client``: each job is then one Dask task, its result sent back to this process,
which writes the job file (workers need no shared file system). On Slurm::

    from dask.distributed import Client
    from dask_jobqueue import SLURMCluster

    cluster = SLURMCluster(cores=16, processes=1, memory="32GB", walltime="04:00:00")
    cluster.scale(jobs=20)                    # 20 Slurm jobs, one Dask worker each
    table = wearsim.study.run("studies/paper-reduced.toml", client=Client(cluster),
                              out="paper-reduced", threads=16)
"""

from __future__ import annotations

import functools
import json
import os
import warnings
from pathlib import Path
from typing import Any, Dict, Optional, Tuple, Union

import pandas as pd

from . import _args, _wearsim
from ._progress import ProgressArg, callback

PathLike = Union[str, os.PathLike]


class Study:
    """An expanded study file."""

    def __init__(self, text: str, base: PathLike, path: Optional[PathLike] = None) -> None:
        self._study = _wearsim.Study(text, Path(base))
        #: The study file, when read from one.
        self.path = None if path is None else Path(path)

    @classmethod
    def from_file(cls, path: PathLike) -> "Study":
        path = Path(path)
        try:
            text = path.read_text()
        except OSError as e:
            raise OSError(f"{path}: cannot read the study file ({e.strerror or e})") from e
        return cls(text, path.resolve().parent, path)

    @property
    def hash(self) -> str:
        """Hash of the parsed study (comments and layout do not count); a result folder is tied to it."""
        return self._study.hash

    @property
    def text(self) -> str:
        return self._study.text

    @property
    def base(self) -> Path:
        """Folder that relative surface paths resolve against."""
        return self._study.base

    def __len__(self) -> int:
        return len(self._study)

    def jobs(self) -> pd.DataFrame:
        """One row per job: index, material, every input and the load (the input columns of the
        tidy results table)."""
        return pd.DataFrame(self._study.jobs())

    def __repr__(self) -> str:
        where = f"{str(self.path)!r}, " if self.path else ""
        return f"Study({where}{len(self)} jobs)"


def load(path: PathLike) -> Study:
    """Reads and expands a study file."""
    return Study.from_file(path)


def _as_study(study: Union[Study, PathLike]) -> Study:
    return study if isinstance(study, Study) else Study.from_file(study)


@functools.lru_cache(maxsize=8)
def _expanded(text: str, base: str) -> Any:
    return _wearsim.Study(text, Path(base))


def _run_job(text: str, base: str, index: int, threads: Optional[int]) -> str:
    """A Dask task: expands the study on the worker and runs job ``index``; returns its result as
    JSON text."""
    return _expanded(text, base).run_job(index, threads)


def _default_out(study: Study) -> Path:
    stem = study.path.stem if study.path else f"study-{study.hash[:8]}"
    return Path.cwd() / f"{stem}-results"


def run(
    study: Union[Study, PathLike],
    client: Any = None,
    *,
    out: Optional[PathLike] = None,
    workers: Optional[int] = None,
    threads: Optional[int] = None,
    shard: Optional[Tuple[int, int]] = None,
    progress: ProgressArg = None,
) -> pd.DataFrame:
    """Runs a study (a :class:`Study` or a study file) into the result folder ``out`` (default:
    ``<study name>-results`` in the working directory), skipping jobs already done there, then
    collects it. Returns the tidy table, equal to the ``results.csv`` of ``wearsim study collect``.

    Without ``client`` the jobs run here, ``workers`` at a time (default: one per thread, as
    ``wearsim study run``) sharing this machine's threads (or ``threads`` of them). With a
    ``dask.distributed.Client`` every pending job is a Dask task (``threads``: threads per task,
    default all of the worker's machine); job files are written here as tasks finish, so a study
    stopped midway (Ctrl-C, a lost allocation) resumes on the next call.
    ``shard=(k, count)`` runs only jobs k−1, k−1+count, … (local runs; the table is then returned
    only when the whole study is done, else an empty DataFrame). ``progress``: True prints jobs
    done on stderr; a callable gets ``(jobs done, jobs to run)``.
    """
    study = _as_study(study)
    out = Path(out) if out is not None else _default_out(study)
    workers = _args.optional_count("workers", workers, 1, fix=", or None for one per thread")
    threads = _args.optional_count("threads", threads, 1, fix=", or None for all cores")
    report = callback(progress, "study: job")
    if client is None:
        outcome = study._study.run(out, workers, shard, threads, report)
        for note in outcome["notes"] + [f"recomputed: {why}" for why in outcome["recomputed"]]:
            warnings.warn(note, stacklevel=2)
        if outcome["claimed_elsewhere"]:
            warnings.warn(
                f"{len(outcome['claimed_elsewhere'])} jobs are being computed by another run on {out}; "
                "collect once it has finished",
                stacklevel=2,
            )
            return pd.DataFrame()
    else:
        if shard is not None:
            raise ValueError("invalid `shard`: with a Dask client the cluster runs every job; drop `shard`")
        from dask.distributed import as_completed

        pending = study._study.prepare(out)
        futures = {
            client.submit(
                _run_job,
                study.text,
                str(study.base),
                index,
                threads,
                key=f"wearsim-{study.hash}-job-{index:06d}",
                pure=False,
            ): index
            for index in pending
        }
        try:
            for done, future in enumerate(as_completed(futures), start=1):
                study._study.write_result(out, futures[future], future.result())
                if report is not None:
                    report(done, len(futures))
        finally:
            for future in futures:
                if not future.done():
                    future.cancel()
    if shard is not None and study._study.prepare(out):
        return pd.DataFrame()
    tidy, _aggregated = collect(out)
    return tidy


def _provenance() -> Dict[str, str]:
    """The versions of this process's software that can change a table: wearsim, Python, NumPy and
    pandas (the job files' own provenance names the Rust crates behind the numbers)."""
    import platform

    import numpy as np

    return {
        "wearsim": _wearsim.__version__,
        "python": platform.python_version(),
        "numpy": np.__version__,
        "pandas": pd.__version__,
    }


def _with_units(table: pd.DataFrame, units: Dict[str, str]) -> pd.DataFrame:
    table.attrs["units"] = {c: u for c, u in units.items() if c in table.columns}
    table.attrs["provenance"] = _provenance()
    return table


def _read_exact(source: Any, text: Optional[Dict[str, Any]] = None) -> pd.DataFrame:
    """One of wearsim's CSV tables, each number read exactly (the files hold the shortest
    round-trip form): pandas 3 does so by default and deprecates asking; older pandas only with
    ``float_precision="round_trip"``, else the last digit may differ, and so would the findings
    judged on the table. ``text``: columns that stay text; empty cells are missing values."""
    if int(pd.__version__.split(".")[0]) >= 3:
        return pd.read_csv(source, dtype=text, keep_default_na=False, na_values=[""])
    return pd.read_csv(source, dtype=text, keep_default_na=False, na_values=[""], float_precision="round_trip")


def collect(out: PathLike) -> Tuple[pd.DataFrame, pd.DataFrame]:
    """Collects a finished result folder, writing ``results.csv`` and ``results_aggregated.csv``
    there as ``wearsim study collect`` does; returns both as DataFrames (tidy: one row per job and
    fracture energy; aggregated: mean, min, max and the 95 % confidence interval of the mean
    (``_ci_low``, ``_ci_high``, Student t over the surface pairs; the method is the
    ``interval_method`` column) of every result over the surface pairs, the results of the fit window
    over the run-in pairs (``fit_window_pairs`` of ``surface_pairs``; all where none is run in), as
    ``wearsim study plot`` and :func:`wearsim.plot.curves` give them)."""
    out = Path(out)
    _wearsim.collect_study(out)
    units = json.loads((out / "results.units.json").read_text())["columns"]
    # Text columns (material names, warnings) stay text even when every cell is empty.
    text = {"material": str, "warnings": str, "surface.top": str, "surface.bottom": str}
    tidy = _read_exact(out / "results.csv", text)
    aggregated = _read_exact(out / "results_aggregated.csv", text)
    for table in (tidy, aggregated):
        for column in ("warnings",):
            if column in table.columns:
                table[column] = table[column].fillna("")
    return _with_units(tidy, units), _with_units(aggregated, units)


def job_series(out: PathLike, job: int) -> pd.DataFrame:
    """The series of one finished job of a study folder: one row per step and fracture energy, the
    library's rows of its job file, with the columns of a sliding run's series
    (:data:`wearsim.wear.SERIES_COLUMNS`); ``static_wear_rate``, ``iterations`` and ``residual``,
    which job files do not keep, are empty, and so are ``merged_junctions`` and ``largest_junction``
    in job files written before they were kept. Lengths in the study's unit."""
    return pd.DataFrame(_wearsim.job_series(Path(out), int(job)))


def findings(tidy: pd.DataFrame) -> Tuple[pd.DataFrame, str]:
    """The paper's findings judged on a study's tidy table under the library's rules (95 % intervals
    over surface pairs, per-pair run-in; the rules ``wearsim study plot`` writes to
    ``figures/findings.md``): one row per finding (key, paper, rule, observed, verdict, counts as
    (holds, contrary, inconclusive, not run in), pairs_to_decide, kind: what kind of result it is,
    verdict_under_holm: the verdict once the units' p-values are Holm-adjusted within the finding,
    where it differs; verdicts_by_rule: for a "rule-dependent" verdict, the verdicts with a pair run in
    by the lineages of s = 0 left, by s_r ≥ 3 ℓ and with every pair kept; same_data_as and reading: for
    a finding whose every unit reads a statistic a finding above it counts, that finding and the
    verdict its own units give; claim: the claim in a few words; notes: what else qualifies it),
    and the text of findings.md, byte for byte what ``wearsim study plot`` writes. A table without a
    run of the sliding model (static estimates only) judges no finding: no row, the columns kept."""
    rows, markdown, _ = _wearsim.findings({str(c): tidy[c].tolist() for c in tidy.columns})
    return pd.DataFrame(rows, columns=None if rows else _FINDING_COLUMNS), markdown


#: The columns of :func:`findings`' table.
_FINDING_COLUMNS = [
    "kind",
    "verdict_under_holm",
    "verdicts_by_rule",
    "same_data_as",
    "reading",
    "claim",
    "notes",
    "key",
    "paper",
    "rule",
    "observed",
    "verdict",
    "counts",
    "pairs_to_decide",
]


def findings_units_csv(tidy: pd.DataFrame) -> str:
    """Every unit of every finding (one row each: finding, unit, outcome, quantity, estimate, low,
    high, n, method, rule, p, p_holm, margin, pairs_to_decide, part, same_data_as, line) as the CSV text that
    ``wearsim study plot`` writes to ``figures/findings_units.csv``."""
    return _wearsim.findings({str(c): tidy[c].tolist() for c in tidy.columns})[2]


def findings_units(tidy: pd.DataFrame) -> pd.DataFrame:
    """:func:`findings_units_csv` as a table."""
    import io

    return _read_exact(io.StringIO(findings_units_csv(tidy)), {"finding": str, "unit": str, "line": str})
