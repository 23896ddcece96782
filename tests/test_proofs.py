"""Every check of proofs/ runs here (those of the full profile under ``-m slow``); the report is
current; verdicts follow the declared methods; the runner's status logic, discovery, packaging and
command line behave as documented."""

from __future__ import annotations

import textwrap
import tomllib
from pathlib import Path

import pytest

from quadric_contact import paper
from quadric_contact.exact.errors import ProofsNotFoundError, QuadricContactError
from quadric_contact.interfaces.cli import main
from quadric_contact.paper.proving import (
    PACKAGE_NAME,
    REPORT_NAME,
    Method,
    Proof,
    Status,
    Verdict,
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
            marks = [pytest.mark.slow] if c.full else []
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
    assert [p.result for p in PROOFS] == list(paper.NUMBERED_RESULTS + paper.FURTHER_RESULTS)


def test_every_erratum_is_demonstrated_by_a_check():
    demonstrated = {c.erratum for p in PROOFS for c in p.checks if c.erratum}
    assert demonstrated == {e.key for e in paper.ERRATA}


def test_every_module_states_claim_method_and_how():
    for p in PROOFS:
        assert p.doc.count("\n") >= 3 and "checked" in p.doc, p.name
        assert p.checks, p.name
        for c in p.checks:
            assert c.method.proves or c.size, (p.name, c.name)


def test_verdicts_follow_the_declarations():
    for p in PROOFS:
        evidence = [c for c in p.checks if c.method is Method.EVIDENCE]
        assert not evidence or p.not_proven, p.name  # evidence supports a part named as not proven
        if p.not_proven:
            assert p.verdict is Verdict.EVIDENCE_ONLY and "Not proven here" in p.doc, p.name
        elif p.errata:
            assert p.verdict is Verdict.PROVEN_WITH_ERRATA, p.name
        else:
            assert p.verdict is Verdict.PROVEN, p.name
        # every erratum is demonstrated by a check that proves
        assert all(c.method.proves for c in p.checks if c.erratum), p.name
        # cross-checks test the package; they are never needed by a proof, so they run in --full only
        assert all(c.full for c in p.checks if c.method is Method.CROSS_CHECK), p.name
        assert set(p.relies_on) <= set(paper.NUMBERED_RESULTS + paper.FURTHER_RESULTS) - {p.result}, p.name


def test_evidence_without_not_proven_is_refused():
    proof = Proof("Remark 16", "test")
    proof.check("a search", method=Method.EVIDENCE, size="3 examples")(lambda: agrees(""))
    with pytest.raises(QuadricContactError, match="not_proven"):
        proof.validate()
    Proof("Remark 16", "test", not_proven="the rest").validate()


def test_the_claims_that_moved_from_evidence_to_proof_are_proofs():
    # Each of these was a search only; each is now proved by the named check.
    proved = {
        ("corollary_10_discriminants", "one_nonreal_pair"): Method.CASES,
        ("corollary_10_discriminants", "criterion_by_configuration"): Method.CASES,
        ("remark_09_non_small", "nonreal_means_crossing"): Method.IDENTITY,
        ("remark_16_plane_center", "centre_side"): Method.IDENTITY,
        ("lemma_12_two_sheets", "root_signs_any_position"): Method.CASES,
        ("theorem_13_table_4", "root_signs_proof"): Method.CASES,
    }
    for (module, check), method in proved.items():
        spec = next(c for c in BY_NAME[module].checks if c.name == check)
        assert spec.method is method and not spec.full, (module, check)
    for name in (
        "corollary_10_discriminants",
        "remark_09_non_small",
        "remark_16_plane_center",
        "lemma_12_two_sheets",
        "theorem_13_table_4",
        "theorem_05_table_2",
    ):
        assert BY_NAME[name].verdict is not Verdict.EVIDENCE_ONLY, name


def test_the_default_profile_has_every_proof_and_no_cross_check():
    for p in PROOFS:
        for c in p.checks:
            if c.method.proves:
                assert not c.full, (p.name, c.name)


def test_errata_state_their_confidence_where_the_extraction_may_be_at_fault():
    by_key = {e.key: e for e in paper.ERRATA}
    for key in (
        "table-4-one-sheet-r-minus",
        "table-4-sign-change-counts",
        "lemma-3-curvature-exponent",
        "table-3-tangent-curve-segre",
    ):
        assert by_key[key].confidence.startswith("low that the printed paper is wrong"), key
        assert "extraction" in by_key[key].confidence, key
    report = (PROOFS_DIR / REPORT_NAME).read_text()
    assert report.count("- **Confidence:**") == sum(1 for e in paper.ERRATA if e.confidence)


def test_module_names_follow_the_numbering():
    for p in PROOFS:
        if p.result in paper.FURTHER_RESULTS and not p.result[-4:].isdigit():
            # the package's own result: named after its label
            assert p.name == p.result.lower().replace("-", " ").replace(" ", "_"), (p.name, p.result)
            continue
        if p.result in paper.FURTHER_RESULTS:  # named after its authors and year instead
            authors, _, year = p.result.rpartition(" ")
            initials = "".join(w[0] for w in authors.split("-")).lower()
            assert p.name.startswith(f"{initials}_{year}_"), (p.name, p.result)
            continue
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


def test_full_profile_checks_are_skipped_in_the_default_profile():
    proof = Proof("Remark 16", "test")
    proof.check("fast", method=Method.IDENTITY)(lambda: agrees("fast"))

    @proof.check("slow", method=Method.IDENTITY, full=True)
    def slow():
        raise AssertionError("must not run")

    record = run_proof(proof, profile="default")
    assert [c.status for c in record.checks] == [Status.PASS, Status.SKIPPED]
    assert record.ok and record.status is Status.PASS and "1 of the full profile not run" in record.line()
    assert run_proof(proof, profile="full").checks[1].status is Status.ERROR


def test_a_check_whose_optional_dependency_is_missing_is_skipped_with_a_note(monkeypatch):
    import quadric_contact.paper.proving as proving

    monkeypatch.setitem(proving.OPTIONAL_DEPENDENCIES, "no_such_package_for_the_proofs", "pip install it")
    proof = Proof("Remark 16", "test")

    @proof.check("needs it", method=Method.IDENTITY, requires=("no_such_package_for_the_proofs",))
    def needs():
        raise AssertionError("must not run")

    record = run_proof(proof, profile="full")
    assert record.checks[0].status is Status.SKIPPED and record.ok
    assert "needs no_such_package_for_the_proofs (pip install it)" in record.line()
    with pytest.raises(ValueError, match="undeclared optional"):
        proof.check("t", method=Method.IDENTITY, requires=("numpy_is_not_optional",))


# -- discovery and selection -------------------------------------------------------------


def test_find_proofs_dir_is_the_checkout_or_an_explicit_dir(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert find_proofs_dir() == PROOFS_DIR
    assert find_proofs_dir(PROOFS_DIR) == PROOFS_DIR
    with pytest.raises(ProofsNotFoundError, match="not a proofs directory"):
        find_proofs_dir(tmp_path)


def _plant_proofs(place: Path) -> Path:
    """A proofs/ folder whose import leaves a mark, as an attacker would plant it."""
    planted = place / "proofs"
    planted.mkdir(parents=True)
    mark = place / "PLANTED_PROOF_RAN"
    (planted / "__init__.py").write_text(f"open({str(mark)!r}, 'w').close()\n")
    (planted / "lemma_99_planted.py").write_text(f"open({str(mark)!r}, 'w').close()\n")
    return mark


def test_a_proofs_folder_planted_above_the_working_directory_is_never_imported(tmp_path, monkeypatch):
    mark = _plant_proofs(tmp_path)
    inside = tmp_path / "a" / "b"
    inside.mkdir(parents=True)
    monkeypatch.chdir(inside)
    assert find_proofs_dir() == PROOFS_DIR
    for where in (inside, tmp_path, tmp_path / "proofs"):
        monkeypatch.chdir(where)
        assert find_proofs_dir() == PROOFS_DIR
    assert not mark.exists()


def test_prove_list_run_below_a_planted_folder_imports_nothing_from_it(tmp_path):
    import subprocess
    import sys

    mark = _plant_proofs(tmp_path)
    (tmp_path / "quadric_contact_proofs").symlink_to(tmp_path / "proofs")  # for `python -m`'s sys.path
    env = {"PYTHONPATH": str(ROOT / "src"), "PATH": "/usr/bin:/bin", "QUADRIC_CONTACT_KERNELS": "wait"}
    done = subprocess.run(
        [sys.executable, "-m", "quadric_contact", "prove", "--list"],
        cwd=tmp_path,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stderr
    assert "lemma_99_planted" not in done.stdout and "Lemma 3" in done.stdout
    assert not mark.exists()


def test_prove_leaves_the_current_directory_empty(tmp_path):
    """A result whose default profile runs a hypothesis search: hypothesis's files go to the user
    cache directory, nothing to the directory ``prove`` runs in."""
    import subprocess
    import sys

    cwd, cache = tmp_path / "cwd", tmp_path / "cache"
    cwd.mkdir()
    env = {
        "PYTHONPATH": str(ROOT / "src"),
        "PATH": "/usr/bin:/bin",
        "HOME": str(tmp_path / "home"),
        "XDG_CACHE_HOME": str(cache),
        "QUADRIC_CONTACT_KERNELS": "wait",  # as the suite: never the background warm-up
    }
    done = subprocess.run(
        [sys.executable, "-m", "quadric_contact", "prove", "wwk_2001_ellipsoid_separation", "-v"],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stdout + done.stderr
    assert "PASS     root_reading_against_geometry" in done.stdout  # the search ran
    assert list(cwd.iterdir()) == []
    assert (cache / "quadric-contact" / "hypothesis").is_dir()


def test_prove_restores_hypothesis_storage(tmp_path, monkeypatch):
    from hypothesis import configuration

    from quadric_contact.interfaces.cli.prove import hypothesis_files_in_the_user_cache

    monkeypatch.delenv("HYPOTHESIS_STORAGE_DIRECTORY", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    before = configuration.storage_directory(intent_to_write=False).home_directory
    with hypothesis_files_in_the_user_cache():
        inside = configuration.storage_directory(intent_to_write=False).home_directory
    assert inside == tmp_path / "quadric-contact" / "hypothesis"
    assert configuration.storage_directory(intent_to_write=False).home_directory == before


def test_no_proofs_dir_is_a_clear_error(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    import quadric_contact.paper.proving as proving

    # the module's place outside a checkout: no pyproject.toml above src/
    place = tmp_path / "src" / "quadric_contact" / "paper" / "proving.py"
    monkeypatch.setattr(proving, "__file__", str(place))
    with pytest.raises(ProofsNotFoundError, match="--proofs-dir DIR") as info:
        find_proofs_dir()
    message = str(info.value)
    assert str(tmp_path / "proofs") in message and str(tmp_path / "src") in message  # where it looked
    assert PACKAGE_NAME in message


def test_the_installed_proofs_are_found_beside_the_package(tmp_path, monkeypatch):
    # A wheel installs proofs/ as the package quadric_contact_proofs beside quadric_contact.
    site = tmp_path / "site-packages"
    installed = site / PACKAGE_NAME
    installed.mkdir(parents=True)
    for f in PROOFS_DIR.glob("*.py"):
        (installed / f.name).write_text(f.read_text())
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    _plant_proofs(elsewhere)
    monkeypatch.chdir(elsewhere)
    import quadric_contact.paper.proving as proving

    monkeypatch.setattr(proving, "__file__", str(site / "quadric_contact" / "paper" / "proving.py"))
    assert find_proofs_dir() == installed.resolve()
    try:
        assert [p.name for p in load_proofs()] == [p.name for p in PROOFS]
    finally:
        load_proofs(PROOFS_DIR)


def test_the_wheel_ships_the_proofs_and_every_package():
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    assert config["package-dir"][PACKAGE_NAME] == "proofs"
    assert "REPORT.md" in config["package-data"][PACKAGE_NAME]
    src = ROOT / "src"
    packages = {".".join(init.parent.relative_to(src).parts) for init in src.rglob("__init__.py")}
    assert set(config["packages"]) == packages | {PACKAGE_NAME}


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
    code = main(["prove", "--proofs-dir", str(PROOFS_DIR), "example_11", "remark_16"])
    out = capsys.readouterr().out.splitlines()
    assert code == 0
    assert out[0].startswith("DIFFERS  example_11_double_root")
    assert "printed Delta_3 = -400; true Delta_3 = -13790208" in out[0]
    assert out[1].startswith("PASS     remark_16_plane_center")
    assert out[2].startswith("2 results") and "(default profile; 1 not run)" in out[2]
    assert "  proven: Remark 16" in out and "  proven, with recorded errata: Example 11" in out


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
        from quadric_contact.paper.proving import Method, Proof, differs
        proof = Proof("Remark 16", "fake")

        @proof.check("wrong", method=Method.IDENTITY)
        def wrong():
            return differs("1 = 2", "1 != 2")
        ''',
    )
    assert main(["prove", "--proofs-dir", str(d)]) == 1
    out = capsys.readouterr().out
    assert out.startswith("FAIL     remark_16_fake") and "unexplained difference" in out
    # --report refuses to write a report the checks do not support.
    assert main(["prove", "--proofs-dir", str(d), "--report"]) == 1
    assert not (d / REPORT_NAME).exists()
    load_proofs(PROOFS_DIR)  # restore the real package for the other tests


def test_cli_bad_names_and_missing_dir_exit_2(tmp_path, capsys, monkeypatch):
    assert main(["prove", "--proofs", str(PROOFS_DIR), "no_such_result"]) == 2
    assert "matches nothing" in capsys.readouterr().err
    assert main(["prove", "--proofs-dir", str(tmp_path)]) == 2
    assert "not a proofs directory" in capsys.readouterr().err


def test_cli_list(capsys):
    assert main(["prove", "--proofs-dir", str(PROOFS_DIR), "--list", "section_3_2"]) == 0
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
        from quadric_contact.paper.proving import Method, Proof, agrees, differs
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
        assert main(["prove", "--proofs-dir", str(d), "--report"]) == 0
        report = (d / REPORT_NAME).read_text()
        row = (
            "| Remark 16 | `remark_16_fake` | proven, with recorded errata | example-11-delta3 | - "
            "| exact computation | 2 |"
        )
        assert row in report
        assert "**Verdict:** proven, with recorded errata (example-11-delta3)." in report
        assert "Claim. One plus one is two." in report
        assert "- **Demonstrated by:** `remark_16_fake::printed`" in report
        assert "- **Demonstrated by:** no proof module" in report  # the other errata, in this fake directory
        assert capsys.readouterr().out.splitlines()[-1].startswith(f"wrote {d / REPORT_NAME} (")
    finally:
        load_proofs(PROOFS_DIR)


def test_cli_default_profile_skips_full_checks(tmp_path, capsys):
    d = _write_fake(
        tmp_path,
        '''
        """Remark 16, fake.

        A claim whose slow check is skipped.
        """
        from quadric_contact.paper.proving import Method, Proof, agrees
        proof = Proof("Remark 16", "fake")

        @proof.check("fast", method=Method.COMPUTATION)
        def fast():
            return agrees("fast")

        @proof.check("slow", method=Method.COMPUTATION, full=True)
        def slow():
            raise AssertionError("not run in the default profile")
        ''',
    )
    try:
        assert main(["prove", "--proofs-dir", str(d)]) == 0
        assert "(1 check; 1 of the full profile not run)" in capsys.readouterr().out
        assert main(["prove", "--proofs-dir", str(d), "--fast"]) == 0  # the old name of the default
        capsys.readouterr()
        assert main(["prove", "--proofs-dir", str(d), "--full"]) == 1  # the full check runs and raises
        assert "ERROR" in capsys.readouterr().out
        assert main(["prove", "--proofs-dir", str(d), "--full", "--fast"]) == 2
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
        assert main(["prove", "--proofs-dir", str(d)]) == 2
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


def test_the_report_is_written_into_a_checkout_only(tmp_path):
    from quadric_contact.paper.proving import write_report

    installed = tmp_path / PACKAGE_NAME
    installed.mkdir()
    for f in PROOFS_DIR.glob("*.py"):
        (installed / f.name).write_text(f.read_text())
    with pytest.raises(QuadricContactError, match="installed with the package"):
        write_report(installed)
    assert not (installed / REPORT_NAME).exists()
