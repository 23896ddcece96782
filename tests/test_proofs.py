"""Every check of proofs/ runs here (slow ones under ``-m slow``); the report is current;
the runner's status logic, discovery and command line behave as documented."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from quadric_contact import paper
from quadric_contact.cli import main
from quadric_contact.errors import ProofsNotFoundError, QuadricContactError
from quadric_contact.proving import (
    REPORT_NAME,
    Method,
    Proof,
    Status,
    agrees,
    differs,
    ensure,
    find_proofs_dir,
    load_proofs,
    render_report,
    run_check,
    run_proof,
    select,
)

ROOT = Path(__file__).resolve().parents[1]
PROOFS_DIR = ROOT / "proofs"
PROOFS = load_proofs(PROOFS_DIR)
BY_NAME = {p.name: p for p in PROOFS}


def _params():
    for p in PROOFS:
        for c in p.checks:
            marks = [pytest.mark.slow] if c.slow else []
            yield pytest.param(p.name, c.name, marks=marks, id=f"{p.name}::{c.name}")


@pytest.mark.parametrize(("module", "check"), list(_params()))
def test_check_matches_its_expectation(module, check):
    spec = next(c for c in BY_NAME[module].checks if c.name == check)
    record = run_check(spec)
    assert record.status is spec.expected_status, f"{record.status}: {record.describe()}"


def test_report_is_current():
    committed = (PROOFS_DIR / REPORT_NAME).read_text()
    assert committed == render_report(PROOFS), (
        "proofs/REPORT.md is out of date: regenerate it with `quadric-contact prove --report`"
    )


def test_every_numbered_result_has_a_module():
    assert [p.result for p in PROOFS] == list(paper.NUMBERED_RESULTS)


def test_every_erratum_is_demonstrated_by_a_check():
    demonstrated = {c.erratum for p in PROOFS for c in p.checks if c.erratum}
    assert demonstrated == {e.key for e in paper.ERRATA}


def test_every_module_states_claim_method_and_how():
    for p in PROOFS:
        assert p.doc.count("\n") >= 3 and "checked" in p.doc, p.name
        assert p.checks, p.name
        for c in p.checks:
            assert c.method is not Method.EVIDENCE or c.size, (p.name, c.name)


def test_module_names_follow_the_numbering():
    for p in PROOFS:
        kind, _, number = p.result.partition(" ")
        if kind == "eq.":
            prefix = f"eq_{int(number.strip('()')):02d}_"
        elif kind == "Section":
            prefix = f"section_{number.replace('.', '_')}_"
        else:
            prefix = f"{kind.lower()}_{int(number):02d}_"
        assert p.name.startswith(prefix), (p.name, prefix)


# -- status logic ------------------------------------------------------------------


def _proof(func, erratum=None):
    proof = Proof("Remark 16", "test")
    proof.check("t", method=Method.IDENTITY, erratum=erratum)(func)
    return proof.checks[0]


def test_status_logic():
    key = paper.ERRATA[0].key
    assert run_check(_proof(lambda: agrees("ok"))).status is Status.PASS
    assert run_check(_proof(lambda: differs("a", "b"), erratum=key)).status is Status.DIFFERS
    unexplained = run_check(_proof(lambda: differs("a", "b")))
    assert unexplained.status is Status.FAIL and "unexplained" in unexplained.message
    gone = run_check(_proof(lambda: agrees("fine now"), erratum=key))
    assert gone.status is Status.FAIL and "no longer reproduced" in gone.message
    unknown = run_check(_proof(lambda: differs("a", "b"), erratum="no-such-erratum"))
    assert unknown.status is Status.FAIL and "not in ERRATA" in unknown.message

    def broken():
        ensure(1 == 2, "one is not two")

    assert run_check(_proof(broken)).status is Status.FAIL

    def raises():
        raise ZeroDivisionError("boom")

    assert run_check(_proof(raises)).status is Status.ERROR
    assert run_check(_proof(lambda: 42)).status is Status.ERROR


def test_evidence_must_state_its_size():
    proof = Proof("Remark 16", "test")
    with pytest.raises(ValueError, match="size"):
        proof.check("t", method=Method.EVIDENCE)(lambda: agrees(""))
    with pytest.raises(ValueError, match="numbered results"):
        Proof("Lemma 99", "nothing")


def test_slow_checks_are_skipped_on_request():
    proof = Proof("Remark 16", "test")
    proof.check("fast", method=Method.IDENTITY)(lambda: agrees("fast"))

    @proof.check("slow", method=Method.IDENTITY, slow=True)
    def slow():
        raise AssertionError("must not run")

    record = run_proof(proof, include_slow=False)
    assert [c.status for c in record.checks] == [Status.PASS, Status.SKIPPED]
    assert record.ok and record.status is Status.PASS and "1 slow skipped" in record.line()


# -- discovery and selection -------------------------------------------------------------


def test_find_proofs_dir_from_root_subdirectories_and_the_dir_itself(tmp_path, monkeypatch):
    assert find_proofs_dir(start=ROOT) == PROOFS_DIR
    assert find_proofs_dir(start=ROOT / "src" / "quadric_contact") == PROOFS_DIR
    assert find_proofs_dir(start=PROOFS_DIR) == PROOFS_DIR
    assert find_proofs_dir(PROOFS_DIR) == PROOFS_DIR
    with pytest.raises(ProofsNotFoundError, match="not a proofs directory"):
        find_proofs_dir(tmp_path)


def test_no_proofs_dir_is_a_clear_error(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    import quadric_contact.proving as proving

    monkeypatch.setattr(proving, "__file__", str(tmp_path / "a" / "b" / "proving.py"))
    with pytest.raises(ProofsNotFoundError, match="--proofs DIR"):
        find_proofs_dir()


def test_select_by_module_prefix_and_label():
    assert [p.name for p in select(PROOFS, ["Lemma 3"])] == ["lemma_03_curvature"]
    assert [p.name for p in select(PROOFS, ["lemma_03"])] == ["lemma_03_curvature"]
    assert [p.result for p in select(PROOFS, ["table 4"])] == ["Theorem 13"]
    with pytest.raises(QuadricContactError, match="matches nothing"):
        select(PROOFS, ["lemma_99"])
    with pytest.raises(QuadricContactError, match="ambiguous"):
        select(PROOFS, ["lemma"])


# -- command line --------------------------------------------------------------------


def test_cli_prints_one_line_per_result(capsys):
    code = main(["prove", "--proofs", str(PROOFS_DIR), "example_11", "remark_16"])
    out = capsys.readouterr().out.splitlines()
    assert code == 0
    assert out[0].startswith("DIFFERS  example_11_double_root")
    assert "printed Delta_3 = -400; true Delta_3 = -13790208" in out[0]
    assert out[1].startswith("PASS     remark_16_plane_center")
    assert out[2].startswith("2 results")


def _write_fake(tmp_path, body):
    d = tmp_path / "proofs"
    d.mkdir()
    (d / "__init__.py").write_text('"""fake proofs"""\n')
    (d / "remark_16_fake.py").write_text(textwrap.dedent(body))
    return d


def test_cli_exit_1_on_an_unexplained_difference(tmp_path, capsys):
    d = _write_fake(
        tmp_path,
        '''
        """Remark 16, fake.

        A claim that is checked to fail.
        """
        from quadric_contact.proving import Method, Proof, differs
        proof = Proof("Remark 16", "fake")

        @proof.check("wrong", method=Method.IDENTITY)
        def wrong():
            return differs("1 = 2", "1 != 2")
        ''',
    )
    assert main(["prove", "--proofs", str(d)]) == 1
    out = capsys.readouterr().out
    assert out.startswith("FAIL     remark_16_fake") and "unexplained difference" in out
    # --report refuses to write a report the checks do not support.
    assert main(["prove", "--proofs", str(d), "--report"]) == 1
    assert not (d / REPORT_NAME).exists()
    load_proofs(PROOFS_DIR)  # restore the real package for the other tests


def test_cli_bad_names_and_missing_dir_exit_2(tmp_path, capsys, monkeypatch):
    assert main(["prove", "--proofs", str(PROOFS_DIR), "no_such_result"]) == 2
    assert "matches nothing" in capsys.readouterr().err
    assert main(["prove", "--proofs", str(tmp_path)]) == 2
    assert "not a proofs directory" in capsys.readouterr().err


def test_cli_list(capsys):
    assert main(["prove", "--proofs", str(PROOFS_DIR), "--list", "section_3_2"]) == 0
    out = capsys.readouterr().out
    assert "delta4" in out and "[erratum delta4-term]" in out


def test_cli_report_writes_a_report_from_the_declarations(tmp_path, capsys):
    d = _write_fake(
        tmp_path,
        '''
        """Remark 16, fake.

        Claim. One plus one is two.

        What is checked and how. The sum is computed.
        """
        from quadric_contact.proving import Method, Proof, agrees, differs
        proof = Proof("Remark 16", "fake")

        @proof.check("one plus one", method=Method.COMPUTATION)
        def sum_():
            return agrees("1 + 1 = 2")

        @proof.check("Example 11's Delta_3", method=Method.COMPUTATION, erratum="example-11-delta3")
        def printed():
            return differs("-400", "-13790208")
        ''',
    )
    try:
        assert main(["prove", "--proofs", str(d), "--report"]) == 0
        report = (d / REPORT_NAME).read_text()
        row = "| Remark 16 | `remark_16_fake` | DIFFERS (example-11-delta3) | exact computation | 2 |"
        assert row in report
        assert "Claim. One plus one is two." in report
        assert "- **Demonstrated by:** `remark_16_fake::printed`" in report
        assert "- **Demonstrated by:** no proof module" in report  # the other errata, in this fake directory
        assert capsys.readouterr().out.rstrip().endswith(f"wrote {d / REPORT_NAME}")
    finally:
        load_proofs(PROOFS_DIR)


def test_cli_fast_skips_slow_checks(tmp_path, capsys):
    d = _write_fake(
        tmp_path,
        '''
        """Remark 16, fake.

        A claim whose slow check is skipped.
        """
        from quadric_contact.proving import Method, Proof, agrees
        proof = Proof("Remark 16", "fake")

        @proof.check("fast", method=Method.COMPUTATION)
        def fast():
            return agrees("fast")

        @proof.check("slow", method=Method.COMPUTATION, slow=True)
        def slow():
            raise AssertionError("not run with --fast")
        ''',
    )
    try:
        assert main(["prove", "--proofs", str(d), "--fast"]) == 0
        assert "(1 check, 1 slow skipped)" in capsys.readouterr().out
        assert main(["prove", "--proofs", str(d)]) == 1  # the slow check runs and raises
        assert "ERROR" in capsys.readouterr().out
    finally:
        load_proofs(PROOFS_DIR)


def test_a_missing_dependency_is_a_clear_error(tmp_path, capsys):
    d = _write_fake(
        tmp_path,
        '''
        """Remark 16, fake.

        Needs a package that does not exist.
        """
        import no_such_package_for_the_proofs  # noqa: F401
        ''',
    )
    try:
        assert main(["prove", "--proofs", str(d)]) == 2
        assert "no_such_package_for_the_proofs" in capsys.readouterr().err
    finally:
        load_proofs(PROOFS_DIR)


def test_intersection_helpers_on_known_configurations():
    from quadric_contact import Quadric

    helpers = __import__("quadric_contact_proofs._intersection", fromlist=["contact_type"])
    sphere, big = Quadric.sphere(1), Quadric.sphere(3)
    assert helpers.contact_type(sphere, big) == "no contact"
    assert helpers.show_segre(helpers.segre(sphere, big)) == "[(111)1]_2"
    touching = Quadric.sphere(1, (2, 0, 0))
    assert helpers.contact_type(touching, Quadric.sphere(1)) == "1 isolated tangent point"
    assert (
        helpers.contact_type(Quadric.sphere(1, (1, 0, 0)), Quadric.sphere(1))
        == "curve with no tangent points"
    )
    for text in ("[1111]_4", "[(11)11]_3", "[2(11)]_2", "[(21)1]_2", "[(211)]_1", "[(11)(11)]_2"):
        assert helpers.show_segre(helpers.parse_segre(text)) == text
