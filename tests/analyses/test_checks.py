"""The paper-claims table (the analysis paper-checks): verdict rules, sideband measures, its rows, its file
and the tables written from it."""

import numpy as np
import pytest

from cradle.analyses import paper_checks as checks
from cradle.analyses.protocol import Read
from cradle.data.io import open_tree, write_netcdf
from cradle.figures import paper_checks as tables
from cradle.measurements import compare, sidebands
from cradle.pipeline import config as cc


@pytest.mark.parametrize("text, unit", [("2e-2", 1e-2), ("2.11", 1e-2), ("52.9", 0.1), ("3.8e-3", 1e-4),
                                        ("175", 1.0), ("1.545", 1e-3)])
def test_printed_unit(text, unit):
    assert checks.printed_unit(text) == pytest.approx(unit)


def test_agrees_within_last_printed_digit():
    assert checks.agrees_printed("2.11", 2.118) == "agrees"        # the paper truncates
    assert checks.agrees_printed("2.11", 2.121) == "disagrees"
    assert checks.agrees_printed("83", 81.8) == "disagrees"
    assert checks.agrees_printed("83", float("nan")) == "not comparable"


def test_sideband_ratio_and_harmonic_height():
    N, q = 200, 4 * np.pi / 5
    n = np.arange(N)
    k, pure = compare.spatial_dft(np.cos(q * n))
    assert sidebands.sideband_ratio(k, np.abs(pure), q) < 1e-12
    side = 2 * np.pi * 60 / N            # well away from +-q and the harmonics
    k, mixed = compare.spatial_dft(np.cos(q * n) + 0.3 * np.cos(side * n) + 0.05 * np.cos(2 * (q - np.pi) * n))
    assert sidebands.sideband_ratio(k, np.abs(mixed), q) == pytest.approx(0.3, rel=1e-9)
    assert sidebands.harmonic_height(k, np.abs(mixed), q, "2(q-pi)") == pytest.approx(0.05, rel=1e-9)


def _texts(rows):
    return [{c: str(getattr(r, c)) for c in checks.COLUMNS} for r in rows]   # in the order of the file


def test_rows_from_closed_forms_and_map():
    rows = checks.closed_forms() + checks.periodic_orbits()
    assert all(r.verdict == "agrees" for r in rows)
    md = tables.to_markdown(_texts(rows))
    assert md.count("\n|") == len(rows) + 2
    csv = tables.to_csv(_texts(rows))
    assert csv.splitlines()[0] == ",".join(checks.COLUMNS)


def test_missing_scenes_leave_their_rows_out():
    rows = checks.rows(checks.PaperChecks(scenes=[], homoclinic=[], analyses=[]), {})
    labels = {r.label for r in rows}
    assert labels == {"(tau0)", "traj2"}


def test_every_row_states_its_tolerance():
    rows = checks.closed_forms() + checks.periodic_orbits()
    assert all(r.tolerance for r in rows)
    assert tables.to_csv(_texts(rows)).splitlines()[0].split(",")[4] == "tolerance"


def test_the_file_holds_the_rows_and_its_tables_write_them_out(tmp_path):
    """compute -> netCDF (one text variable per column, one entry per row) -> the CSV and Markdown tables,
    the same text as the rows themselves give."""
    spec = checks.PaperChecks(scenes=[], homoclinic=[], analyses=[])
    rows = checks.rows(spec, {})
    tree = open_tree(write_netcdf(checks.compute(spec, {}), tmp_path / "paper-checks.nc"))
    ds = tree.to_dataset()
    assert ds.sizes["row"] == len(rows) and list(ds["verdict"].values) == [r.verdict for r in rows]
    assert ds.attrs["n_agrees"] == len(rows) and ds.attrs["n_disagrees"] == 0
    out = tables.tables(tree)
    assert out == {"csv": tables.to_csv(_texts(rows)), "md": tables.to_markdown(_texts(rows))}
    assert f"{len(rows)} statements: {len(rows)} agrees, 0 disagrees, 0 not comparable." in out["md"]


def test_its_spec_names_every_scene_and_homoclinic_of_the_config_and_reads_them_by_name():
    from pathlib import Path

    import yaml

    raw = yaml.safe_load((Path(__file__).resolve().parents[2] / "config.yaml").read_text())
    spec = cc.analysis_spec(raw, "paper-checks", "full")
    # in name order: the table does not depend on the order of the config's blocks, so neither do its params
    assert spec.scenes == sorted(raw["scenes"]) and sorted(spec.homoclinic) == sorted(raw["homoclinic"])
    reads = checks.ANALYSIS.reads_of(spec)
    assert len(reads) == 4 * len(raw["scenes"]) + len(raw["homoclinic"]) + len(checks.claiming_analyses())
    assert reads["analysis/travelling-breathers"] == Read.of("analysis", analysis="travelling-breathers")
    assert reads["fft106/metrics"] == Read.of("metrics", scene="fft106")
    assert reads["homoclinic/site"] == Read.of("homoclinic", name="site")
    raw.setdefault("beyond", {})["paper-checks"] = {"scenes": ["tw-weak"], "homoclinic": [], "analyses": []}
    assert set(checks.ANALYSIS.reads_of(cc.analysis_spec(raw, "paper-checks", "full"))) == {
        "tw-weak/initial", "tw-weak/exact", "tw-weak/dps", "tw-weak/metrics"}


def test_the_table_collects_the_claims_rows_an_analysis_declares_after_the_papers():
    """An analysis's claims group (claims_table.group) read back by the table: its rows after the paper's, which
    are unchanged, a qualitative one marked so in its tolerance cell, each naming the analysis; the groups are
    found by the declaration (Analysis.claims), and the two analyses of issue 37 declare theirs."""
    import xarray as xr

    from cradle.analyses.claims_table import Row, group

    assert {"travelling-breathers", "continuum-limit"} <= set(checks.claiming_analyses())
    mine = [Row("Xu et al.", "q", "a change", "none", "agrees", "m", "one grid spacing", "a.md#x", qualitative=True),
            Row("Someone 2020", "n", "1.5", "1.52", "disagrees", "fit", "+-0.1", "b.md#y")]
    data, coords = group(mine)
    tree = xr.DataTree.from_dict({"/": xr.Dataset(), "/claims": xr.Dataset(
        {k: ("row", v) for k, v in data.items()}, coords={"row": coords["row"]})})
    paper = checks.rows(checks.PaperChecks(scenes=[], homoclinic=[], analyses=[]), {})
    both = checks.rows(checks.PaperChecks(scenes=[], homoclinic=[], analyses=["travelling-breathers"]),
                       {"analysis/travelling-breathers": tree})
    assert both[:len(paper)] == paper and len(both) == len(paper) + 2
    got = both[len(paper):]
    assert got[0].tolerance == "qualitative: one grid spacing" and got[0].qualitative
    assert got[1].tolerance == "+-0.1" and not got[1].qualitative
    assert [r.measured for r in got] == ["m (analysis travelling-breathers)", "fit (analysis travelling-breathers)"]
    assert [r.explained_in for r in got] == ["a.md#x", "b.md#y"]


def test_another_analysis_is_read_from_the_output_of_the_form_all_builds_as_a_tree():
    """The file a Read of kind analysis names is that analysis's output of its first form (the one `all` builds),
    and the layout knows it as an analysis output (the compute job opens such an input as the tree of its groups)."""
    from cradle.analyses.registry import ANALYSES
    from cradle.pipeline import layout
    from cradle.pipeline.identity import locate

    for name in checks.claiming_analyses():
        main = ANALYSES[name].forms[0]
        path = layout.read_path(Read.of("analysis", analysis=name), "full")
        assert path == layout.analysis_output(name, main, main)
        assert locate(path) == ("analysis", {"analysis": name, "form": main})


def test_an_analysis_named_without_claims_is_refused_in_one_line():
    from cradle.specs.values import Errors

    out = Errors()
    checks.PaperChecks(analyses=["travelling-breathers", "floquet"]).check(["beyond", "paper-checks"], None, out)
    assert len(out.lines) == 1
    assert out.lines[0].startswith("config error: beyond.paper-checks.analyses[1] = 'floquet': ")


def test_a_harmonic_is_a_coherent_peak_above_the_local_band():
    """A pure harmonic on a flat floor stands far above its band; the same height inside a broad band of
    random-phase modes (an instability band, fft344 DpS) does not."""
    N, q = 200, 57 * np.pi / 100
    n = np.arange(N)
    h = 2 * (q - np.pi)
    k, coherent = compare.spatial_dft(np.cos(q * n) + 0.07 * np.cos(h * n) + 1e-3 * np.cos(0.3 * n))
    assert sidebands.harmonic_over_band(k, np.abs(coherent), q, "2(q-pi)") > 50
    rng = np.random.default_rng(20261122)
    band = sum(0.07 * np.cos(2 * np.pi * j / N * n + rng.uniform(0, 2 * np.pi))
               for j in range(round(h * N / (2 * np.pi)) - 12, round(h * N / (2 * np.pi)) + 13))
    k, broad = compare.spatial_dft(np.cos(q * n) + band)
    assert sidebands.harmonic_height(k, np.abs(broad), q, "2(q-pi)") > checks.HARMONIC_PRESENT
    assert sidebands.harmonic_over_band(k, np.abs(broad), q, "2(q-pi)") < checks.PEAK_OVER_BAND


def _doctable():
    import importlib.util
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    spec = importlib.util.spec_from_file_location("doctable", root / "benchmarks" / "doctable.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return root, module


def test_every_explanation_a_claim_declares_exists():
    """The paragraphs the claims point at ("<page>.md#<anchor>" under docs/, beside each claim in the
    analyses' modules): the page has the anchor."""
    import re

    root, doctable = _doctable()
    declared = set()
    for module in (root / "src" / "cradle" / "analyses").glob("*.py"):
        declared |= set(re.findall(r'"([\w-]+\.md#[\w-]+)"', module.read_text()))
    assert {checks.FFTSEUIL, checks.HARMONICS, checks.LOC1_MERGING} <= declared
    assert [w for w in declared if not doctable.link_resolves(root / "docs" / "x.md", w)] == []


def test_a_disagreement_links_to_its_explanation():
    """In the Markdown table a verdict other than agrees links to its paragraph, relative to where the layout
    puts the table; one with no paragraph says so."""
    from pathlib import Path

    from cradle.analyses.claims_table import Row, explained
    from cradle.pipeline import layout

    root, doctable = _doctable()
    rows = explained(checks.HARMONICS, [Row("fft344", "h", "yes", "no", "disagrees", "m", "t"),
                                        Row("fft344", "h", "no", "no", "agrees", "m", "t"),
                                        Row("fft344", "h", "yes", "no", "disagrees", "m", "t", "analyses.md#x")])
    rows.append(Row("loc1", "m", "175", "223", "disagrees", "m", "t"))
    md = tables.to_markdown(_texts(rows))
    lines = md.splitlines()[-4:]
    link = f"{tables.DOCS_FROM_TABLE}{checks.HARMONICS}"
    assert f"| disagrees ([why]({link})) |" in lines[0]
    assert "| agrees |" in lines[1] and "analyses.md#x" in lines[2] and "(no explanation yet)" in lines[3]
    assert "explained_in" not in md.splitlines()[4]                   # the header: the link is in the verdict
    table = Path(layout.analysis_tables("paper-checks", "full", "full", ("md",), root=root / "results")["md"])
    assert doctable.link_resolves(table, link)


def test_every_disagreement_of_the_built_table_is_explained():
    """The table of the build in results/ (when there is one): every row that does not agree names a paragraph
    that exists."""
    from pathlib import Path

    from cradle.pipeline import layout

    root, doctable = _doctable()
    path = Path(layout.analysis_output("paper-checks", "full", "full", root=root / "results"))
    if not path.exists():
        pytest.skip(f"{path} absent: no built claims table to check (snakemake -j2 paper_checks builds it)")
    ds = open_tree(path).to_dataset()
    if "explained_in" not in ds:
        pytest.skip(f"{path} was written before rows named their explanations: rebuild it")
    rows = [(str(v), str(w), str(lab)) for v, w, lab in zip(ds["verdict"].values, ds["explained_in"].values,
                                                           ds["label"].values, strict=True)]
    unexplained = [(lab, w) for v, w, lab in rows
                   if v != "agrees" and not (w and doctable.link_resolves(root / "docs" / "x.md", w))]
    assert unexplained == []
