"""cradle.pipeline.restored: a file given back in place keeps its old time; a file replaced does not."""
import os

from cradle.pipeline.restored import restore_times, snapshot


def test_a_file_copied_back_in_place_gets_its_old_time_and_a_replaced_one_keeps_its_new(tmp_path):
    kept, replaced, grown = (tmp_path / n for n in ("kept.nc", "replaced.nc", "grown.nc"))
    for f in (kept, replaced, grown):
        f.write_bytes(b"old values")
        os.utime(f, ns=(1_000_000_000, 1_000_000_000))
    before = snapshot(tmp_path)
    kept.write_bytes(b"old values")            # what Snakemake's restore does: the same bytes, written in place
    new = tmp_path / ".replaced.tmp"
    new.write_bytes(b"new values")
    os.replace(new, replaced)                  # what a finished job does: a new file renamed over the target
    grown.write_bytes(b"old values, more")     # same file, other content
    assert restore_times(before) == [str(kept)]
    assert kept.stat().st_mtime_ns == 1_000_000_000
    assert replaced.stat().st_mtime_ns != 1_000_000_000
    assert grown.stat().st_mtime_ns != 1_000_000_000


def test_a_missing_folder_has_an_empty_snapshot(tmp_path):
    assert snapshot(tmp_path / "results") == {}
    assert restore_times({str(tmp_path / "gone.nc"): (1, 2, 3)}) == []
