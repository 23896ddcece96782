import json

from quadric_contact.interfaces.cli import main


def test_check_default_pair_reports_every_step(capsys):
    code = main(["check", "--small", "yes"])
    out = capsys.readouterr().out
    assert code == 0
    for needle in ("P(lambda)", "Delta3", "Delta4", "-+++", "Corollary 10", "R+", "Theorem 13 / Table 4"):
        assert needle in out


def test_check_json(capsys):
    code = main(["check", "--json", "2*x**2 + 2*y**2 + 3*z**2 - 1", "x**2 + y**2 + 8*z"])
    data = json.loads(capsys.readouterr().out)
    assert code == 0
    assert data["contact"]["transversal_contact"] is True
    assert data["contact"]["decided_by"] == "Remark 9"
    assert data["region"]["region"] == "contact"


def test_check_plane(capsys):
    assert main(["check", "(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1", "z - 6"]) == 0
    assert "Algorithm 1 zone 2" in capsys.readouterr().out


def test_bad_input_exits_2_with_message(capsys):
    assert main(["check", "x**2 + y**2 + z**2 - 1", "x**3"]) == 2
    assert "degree 3" in capsys.readouterr().err
    assert main(["check", "x**2 + y**2 - z**2 - 1", "z"]) == 2
    assert "expected a real ellipsoid" in capsys.readouterr().err


def test_undecided_exits_3(capsys):
    assert main(["check", "--small", "no", "--method", "theory", "x**2+y**2+z**2-1", "x**2+y**2-4"]) == 3
    assert "UNDECIDED" in capsys.readouterr().out
