"""The paper's cases at the chosen setting (georod_tools.studies.paper_setting): the recorded
settings file, and ``study paper --setting both`` end to end with short runs."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from georod_tools.studies.paper_setting import SETTINGS_FILE, PaperSetting, load_setting

needs_fmu = pytest.mark.usefixtures("fmu_paths")


def test_settings_file_is_complete_and_loads() -> None:
    data = json.loads(SETTINGS_FILE.read_text())
    for key in ("pre_shortening", "elements", "steps_per_period"):
        assert key in data, key
    s = load_setting()
    assert s.name == "chosen" and not s.is_literal
    # the end shortening stays within the paper's two digits (0.105 <= x < 0.115)
    assert 0.105 <= s.pre_shortening < 0.115
    assert PaperSetting().is_literal


def test_unknown_keys_are_refused(tmp_path: Path) -> None:
    bad = tmp_path / "s.json"
    bad.write_text(json.dumps({"pre_shortening": 0.108, "elemnts": 10}))
    with pytest.raises(ValueError, match="elemnts"):
        load_setting(bad)


@needs_fmu
def test_study_paper_both_settings_quick(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """26 panels at both settings (short runs), the side-by-side table with its counts, each
    setting in its own folder, the chosen one's scene packaged there. A smoke version of
    --quick: 20 + 30 periods a case instead of 150 + 100 (what is checked here is the tables
    and folders, not the motions; the motions are test_analysis_fmu.py's)."""
    from georod_tools.cli import main
    from georod_tools.studies.paper import StudySettings

    def smoke(cls: type[StudySettings], fmu: str) -> StudySettings:
        return cls(fmu=fmu, transient=20, periods=30, dense_periods=5, bif_count=2)

    monkeypatch.setattr(StudySettings, "quick", classmethod(smoke))

    settings = tmp_path / "s.json"
    settings.write_text(json.dumps({"pre_shortening": 0.108, "elements": 10, "mass": "lumped"}))
    out = tmp_path / "paper"
    argv = ["study", "paper", "--quick", "--setting", "both", "--settings-file", str(settings)]
    argv += ["--parts", "cases", "--no-convergence", "--no-progress", "--out", str(out)]
    assert main(argv) == 0
    table = (out / "table_cases_side_by_side.md").read_text()
    assert table.count("| fig") == 26
    assert "Chosen setting (pre_shortening 0.108, 10 elements, T/128, lumped mass)" in table
    assert (out / "chosen" / "scene" / "BuckledBeam_chosen.fmu").is_file()
    assert "lumped" in (out / "chosen" / "scene" / "BuckledBeam_chosen.toml").read_text()
    for name in ("literal", "chosen"):
        assert (out / name / "table_cases.md").read_text().count("| fig") == 26
    record = json.loads((out / "run.json").read_text())
    assert record["settings"]["setting"]["chosen"]["pre_shortening"] == 0.108
