"""A study's results table on disk: Parquet part files, a fixed schema, safe to kill.

Layout of a store directory::

    manifest.json          study name, study hash (and its parts), schema, gfbopt provenance
    parts/part-*.parquet   one file per batch of finished points
    set-aside/             damaged or foreign parts moved aside by a resume (never deleted)

and beside it ``.<store>.lock``, held (``flock``) by the run that writes the store.

* **Never lost.** Each part is written under a temporary name and moved into place with
  ``os.replace`` (atomic on POSIX), so a process killed at any moment (``kill -9``
  included) leaves only whole parts; a half-written ``.part-*.tmp`` is removed when the store
  is next opened and its points are computed again.  One schema, fixed when the store is
  created, is applied to every part and to the read (a directory of parts read without one
  silently drops columns that appear later).
* **Never mixed.** A run takes the store's lock (:func:`lock_store`): a second run on the
  same folder is refused in one line naming the holder (pid, host, start).  Every part
  carries the study hash in its metadata and is checked on read; a resume is refused when
  the manifest's hash differs, naming the inputs that changed.  A directory of parts without
  its manifest is never taken over: a fresh run moves it aside (saying so), a resume refuses.
* **Damage is one line.** A part that cannot be read (or belongs to another study) makes
  :meth:`ResultStore.read` raise one ParameterError naming the part; ``--resume`` moves it
  to ``set-aside/`` and its points are computed again.

Every row carries the point key (``point``); :meth:`ResultStore.read` returns each point once
(the last write wins), so a resumed study ends with every point exactly once.  Rows whose
failure was infrastructural (a worker that died, a task cancelled — written by gfbopt 0.2.0)
are not counted as done (:func:`is_infrastructure_message`), so a resume computes them again.
"""
from __future__ import annotations

import contextlib
import datetime as _dt
import json
import os
import re
import socket
import sys
import uuid
from pathlib import Path
from typing import Iterable, Iterator, Optional

import numpy as np
import pandas as pd

from ..errors import ParameterError

#: Column types a schema may use, and their pyarrow types.
TYPES = ("float64", "int64", "bool", "string")
#: Version of the study hash written in the manifest; a store made with another version
#: cannot be resumed (its hash means something else).
HASH_VERSION = 2
#: Messages of failures that were not results of the point (workers lost, tasks cancelled).
_INFRASTRUCTURE = re.compile(r"BrokenProcessPool|the worker process died|CancelledError|"
                             r"KilledWorker|CommClosedError|scheduler .*lost")


def is_infrastructure_message(message) -> bool:
    """True for the message of a row that failed because of the executor, not the analysis."""
    return isinstance(message, str) and bool(_INFRASTRUCTURE.search(message))


def _arrow_schema(schema: dict):
    import pyarrow as pa

    kinds = {"float64": pa.float64(), "int64": pa.int64(), "bool": pa.bool_(),
             "string": pa.string()}
    return pa.schema([(name, kinds[kind]) for name, kind in schema.items()])


def _unknown_columns(rows: list[dict], schema: dict) -> None:
    """A column the schema does not know is refused: it would be lost on read."""
    extra = sorted(set().union(*rows) - set(schema))
    if extra:
        raise ParameterError("row", extra[0], f"is not a column of this study's table "
                             f"(schema: {', '.join(schema)})")


def _conform(rows: list[dict], schema: dict) -> pd.DataFrame:
    """Rows → a DataFrame with exactly the schema's columns and types (missing → null).

    A column the schema does not know is refused: it would be lost on read.
    """
    _unknown_columns(rows, schema)
    frame = pd.DataFrame.from_records(rows, columns=list(schema))
    for name, kind in schema.items():
        frame[name] = _pandas_column(frame[name], kind)
    return frame


def _pandas_column(col: pd.Series, kind: str) -> pd.Series:
    """One column coerced to its kind as pandas does it (strings to numbers, NaN to null)."""
    if kind == "float64":
        return pd.to_numeric(col, errors="coerce").astype("float64")
    if kind == "int64":
        return pd.to_numeric(col, errors="coerce").astype("Int64")
    if kind == "bool":
        return col.astype("boolean")
    return col.astype("string")


#: Python types a column of each kind takes to pyarrow as they are (None is null; a float
#: NaN in a float64 column is null, as pandas makes it); any other type (a number in a
#: string column, a string in a number column) goes through :func:`_pandas_column`.
_DIRECT = {"float64": (float, int, np.float64, np.float32, np.int64, np.int32, type(None)),
           "int64": (int, np.int64, np.int32, type(None)),
           "bool": (bool, np.bool_, type(None)),
           "string": (str, type(None))}


def _conform_table(rows: list[dict], schema: dict):
    """Rows → a pyarrow Table of the schema's columns and types: the rows and types
    :func:`_conform` gives (then ``Table.from_pandas``), without building a DataFrame.

    ``Table.from_pylist`` with the fixed schema, a float NaN then made null as pandas makes
    it; an int64 column holding anything but integers (pyarrow would truncate 2.5 to 2), or
    any value pyarrow refuses, takes :func:`_by_column`.  A part of 4 rows: 0.08 ms against
    1.9 ms; 400 rows: 0.3 ms against 2.3 ms; 10⁴ rows: 7.6 ms against 11.7 ms (CPU,
    benchmarks/bench_pool_stream.py)."""
    import pyarrow as pa
    import pyarrow.compute as pc

    _unknown_columns(rows, schema)
    arrow = _arrow_schema(schema)
    plain = all(set(map(type, (row.get(name) for row in rows))).issubset(_DIRECT["int64"])
                for name, kind in schema.items() if kind == "int64")
    if not plain:
        return _by_column(rows, schema, arrow)
    try:
        table = pa.Table.from_pylist(rows, schema=arrow)
    except (pa.ArrowInvalid, pa.ArrowTypeError, OverflowError, TypeError, ValueError):
        return _by_column(rows, schema, arrow)
    for k, field in enumerate(arrow):
        if schema[field.name] == "float64":
            nan = pc.is_nan(table.column(k))
            if pc.any(nan).as_py():
                column = pc.if_else(nan, pa.scalar(None, pa.float64()), table.column(k))
                table = table.set_column(k, field, column)
    return table


def _by_column(rows: list[dict], schema: dict, arrow):
    """:func:`_conform_table` column by column: a column of the types in :data:`_DIRECT`
    goes to pyarrow directly, any other through :func:`_pandas_column`."""
    import pyarrow as pa

    columns = []
    for field in arrow:
        values = [row.get(field.name) for row in rows]
        column = None
        if set(map(type, values)).issubset(_DIRECT[schema[field.name]]):
            try:
                column = pa.array(values, type=field.type, from_pandas=True)
            except (pa.ArrowInvalid, pa.ArrowTypeError, OverflowError):
                column = None     # e.g. an integer a double cannot hold exactly: pandas rounds
        if column is None:
            series = _pandas_column(pd.Series(values, dtype=object), schema[field.name])
            column = pa.array(series, type=field.type, from_pandas=True)
        columns.append(column)
    return pa.Table.from_arrays(columns, schema=arrow)


# ---------------------------------------------------------------------- the lock
def _lock_path(directory: Path) -> Path:
    return directory.parent / f".{directory.name}.lock"


@contextlib.contextmanager
def lock_store(directory) -> Iterator[Path]:
    """Hold the lock of the store ``directory`` for the duration of the ``with`` block.

    The lock is an ``flock`` on ``.<store>.lock`` beside the store (released by the kernel
    when the holder dies, so a ``kill -9`` leaves no stale lock).  A second holder is refused
    with one ParameterError naming the running one.
    """
    import fcntl

    directory = Path(directory)
    path = _lock_path(directory)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            try:
                holder = json.loads(os.pread(fd, 4096, 0).decode() or "{}")
            except (ValueError, OSError):
                holder = {}
            who = (f"pid {holder.get('pid', '?')} on {holder.get('host', '?')}, started "
                   f"{holder.get('started', '?')}: {holder.get('command', '?')}")
            raise ParameterError("results", str(directory), f"is being written by another "
                                 f"gfbopt run ({who}); wait for it to end or give another "
                                 "--results folder") from None
        text = json.dumps({"pid": os.getpid(), "host": socket.gethostname(),
                           "started": _dt.datetime.now(_dt.timezone.utc).isoformat(
                               timespec="seconds"),
                           "command": " ".join(sys.argv)[:300]})
        os.ftruncate(fd, 0)
        os.pwrite(fd, text.encode(), 0)
        yield path
    finally:
        os.close(fd)            # releases the flock


# ---------------------------------------------------------------------- manifest
def _read_manifest(directory: Path) -> Optional[dict]:
    path = directory / "manifest.json"
    if not path.is_file():
        return None
    try:
        manifest = json.loads(path.read_text())
        if not isinstance(manifest, dict) or "schema" not in manifest:
            raise ValueError("no schema")
    except (ValueError, UnicodeDecodeError) as exc:
        raise ParameterError("results", str(path), f"is not a readable gfbopt store manifest "
                             f"({type(exc).__name__}); move the store aside") from None
    return manifest


def _aside(directory: Path, tag: str) -> Path:
    k = 1
    while Path(f"{directory}.{tag}-{k}").exists():
        k += 1
    target = Path(f"{directory}.{tag}-{k}")
    os.replace(directory, target)
    return target


def _changed(old: dict, new: dict) -> str:
    """Which hashed inputs differ between two manifests (their ``inputs`` digests)."""
    a, b = old.get("inputs") or {}, new or {}
    keys = [k for k in sorted(set(a) | set(b)) if a.get(k) != b.get(k)]
    return ", ".join(keys) if keys and a else "the study's inputs"


class ResultStore:
    """One study's table of results on disk (see the module docstring).

    Use :meth:`create` to start (or resume) a store and :meth:`append` to add finished rows;
    :meth:`read` returns the whole table as one DataFrame.  ``notices`` lists what opening
    the store did that a user should know (parts moved aside, temporary files removed).
    """

    def __init__(self, directory: Path, manifest: dict):
        self.directory = Path(directory)
        self.manifest = manifest
        self.schema: dict = manifest["schema"]
        self.notices: list[str] = []

    # ------------------------------------------------------------------ opening
    @classmethod
    def create(cls, directory, *, study: str, study_hash: str, schema: dict,
               metadata: Optional[dict] = None, resume: bool = False,
               inputs: Optional[dict] = None, study_file: str = "") -> "ResultStore":
        """Open the store in ``directory`` for study ``study`` (hash ``study_hash``).

        resume=False: an existing store is kept aside (renamed ``<dir>.previous-N``; a
        directory without manifest ``<dir>.orphan-N``) and a new one started — nothing
        computed is ever deleted.  resume=True: the existing store is reused; it must hold
        the same study (same hash, ``inputs`` names what changed otherwise), and its damaged
        or foreign parts are moved to ``set-aside/`` so their points are computed again.
        Call it while holding :func:`lock_store`.
        """
        directory = Path(directory)
        for name, kind in schema.items():
            if kind not in TYPES:
                raise ParameterError(f"schema.{name}", kind, f"must be one of {', '.join(TYPES)}")
        if "point" not in schema:
            raise ParameterError("schema", list(schema), "must contain the point key 'point'")
        notices = []
        old = _read_manifest(directory)
        if old is not None:
            if resume:
                store = cls._resumed(directory, old, study, study_hash, inputs, study_file)
                return store
            moved = _aside(directory, "previous")
            notices.append(f"the previous store was kept as {moved}")
        elif directory.exists() and any(directory.iterdir()):
            if resume:
                raise ParameterError("--resume", str(directory), "holds files but no "
                                     "manifest.json, so they cannot be checked against this "
                                     "study; run without --resume (they are moved aside)")
            moved = _aside(directory, "orphan")
            notices.append(f"{directory} had parts but no manifest.json: moved aside to "
                           f"{moved} (not used)")
        (directory / "parts").mkdir(parents=True, exist_ok=True)
        manifest = {"study": study, "study_hash": study_hash, "hash_version": HASH_VERSION,
                    "inputs": inputs or {}, "schema": schema, "metadata": metadata or {}}
        tmp = directory / f".manifest.{uuid.uuid4().hex}.tmp"
        tmp.write_text(json.dumps(manifest, indent=2, default=str))
        os.replace(tmp, directory / "manifest.json")
        store = cls(directory, manifest)
        store.notices = notices
        return store

    @classmethod
    def _resumed(cls, directory, old, study, study_hash, inputs, study_file) -> "ResultStore":
        if old.get("hash_version") != HASH_VERSION:
            raise ParameterError("--resume", str(directory), "was written by an older gfbopt "
                                 "whose study hash is not comparable; run without --resume "
                                 "(the old store is kept aside)")
        if old.get("study_hash") != study_hash:
            held = (old.get("metadata") or {}).get("study_file") or old.get("study")
            what = f"{held}" if held == study_file else f"study {held!r}"
            raise ParameterError(
                "--resume", str(directory), f"holds results of {what} with other inputs "
                f"(changed: {_changed(old, inputs)}); refusing to mix them. Restore those "
                "inputs to resume, or run without --resume to start afresh (the old store "
                "is kept aside)")
        store = cls(directory, old)
        store.notices += store._clean()
        return store

    def _clean(self) -> list[str]:
        """Remove temporary files of interrupted writes; move unreadable and foreign parts
        to ``set-aside/`` (their points are computed again)."""
        notes = []
        parts = self.directory / "parts"
        parts.mkdir(parents=True, exist_ok=True)
        stale = list(parts.glob(".part-*.tmp")) + list(self.directory.glob(".manifest.*.tmp"))
        for tmp in stale:
            tmp.unlink(missing_ok=True)
        if stale:
            notes.append(f"removed {len(stale)} temporary file(s) left by an interrupted write")
        for path, problem in self._problems():
            aside = self.directory / "set-aside"
            aside.mkdir(exist_ok=True)
            os.replace(path, aside / path.name)
            notes.append(f"{path.name} {problem}: moved to {aside}; its points are "
                         "computed again")
        return notes

    # ------------------------------------------------------------------ writing
    def append(self, rows: Iterable[dict]) -> Optional[Path]:
        """Write ``rows`` as one new part (atomic); returns its path (None if no rows)."""
        import pyarrow.parquet as pq

        rows = list(rows)
        if not rows:
            return None
        table = _conform_table(rows, self.schema).replace_schema_metadata(
            {"gfbopt": json.dumps({"study": self.manifest["study"],
                                   "study_hash": self.manifest["study_hash"],
                                   **self.manifest.get("metadata", {})}, default=str)})
        name = f"part-{uuid.uuid4().hex}.parquet"
        tmp = self.directory / "parts" / f".{name}.tmp"
        try:
            pq.write_table(table, tmp)
            os.replace(tmp, self.directory / "parts" / name)
        except BaseException:
            tmp.unlink(missing_ok=True)
            raise
        return self.directory / "parts" / name

    # ------------------------------------------------------------------ reading
    def parts(self) -> list[Path]:
        """The finished part files (temporary files of an interrupted write excluded)."""
        return sorted((self.directory / "parts").glob("part-*.parquet"),
                      key=lambda p: (p.stat().st_mtime_ns, p.name))

    def _read_part(self, path: Path):
        """(table, None) or (None, what is wrong with the part)."""
        import pyarrow.parquet as pq

        try:
            handle = pq.ParquetFile(path)
            meta = (handle.schema_arrow.metadata or {}).get(b"gfbopt", b"{}")
            owner = json.loads(meta.decode())
            if owner.get("study_hash") != self.manifest["study_hash"]:
                return None, (f"belongs to another study (hash "
                              f"{str(owner.get('study_hash'))[:12]})")
            table = pq.read_table(path, schema=_arrow_schema(self.schema))
            return table.replace_schema_metadata(None), None
        except Exception as exc:  # noqa: BLE001 - any unreadable file is reported the same way
            first = (str(exc).splitlines() or [""])[0][:100]
            return None, f"is damaged ({type(exc).__name__}: {first})"

    def _problems(self) -> list[tuple[Path, str]]:
        return [(p, problem) for p in self.parts()
                for _, problem in [self._read_part(p)] if problem]

    def read(self) -> pd.DataFrame:
        """The whole table, one row per point (last write wins), sorted by point.

        A damaged or foreign part raises one ParameterError naming it (``--resume`` moves
        such parts aside and computes their points again)."""
        import pyarrow as pa

        tables = []
        for path in self.parts():
            table, problem = self._read_part(path)
            if problem:
                raise ParameterError("results", str(path), f"{problem}; run the study with "
                                     "--resume to move it aside and compute its points again")
            tables.append(table)
        if not tables:
            return _conform([], self.schema)
        frame = pa.concat_tables(tables).to_pandas()
        frame = frame.drop_duplicates(subset="point", keep="last")
        return frame.sort_values("point").reset_index(drop=True)

    def rows_written(self) -> int:
        """Rows in every part, a point written twice counted twice (:meth:`read` keeps the
        last of them)."""
        import pyarrow.parquet as pq

        return sum(pq.ParquetFile(p).metadata.num_rows for p in self.parts())

    def done_points(self) -> set:
        """Point keys already stored (skipped on resume); a row whose failure was
        infrastructural is not done."""
        frame = self.read()
        if "message" in frame.columns and "success" in frame.columns:
            failed = ~frame["success"].fillna(False).astype(bool).to_numpy()
            infra = [is_infrastructure_message(m) for m in frame["message"].tolist()]
            frame = frame[~(failed & np.array(infra, dtype=bool))]
        return set(frame["point"].tolist())


def read_results(directory) -> pd.DataFrame:
    """The results table of a study store directory as one pandas DataFrame."""
    directory = Path(directory)
    manifest = _read_manifest(directory)
    if manifest is None:
        raise ParameterError("results", str(directory), "is not a gfbopt results store (no "
                             "manifest.json)")
    return ResultStore(directory, manifest).read()
