"""Parameter sweeps on a Dask LocalCluster: one row per set, a bad set a row with its error."""
import numpy as np

import fascia


def test_sweep_of_8_runs_on_2_workers(cube_xml, tmp_path):
    sets = [{"body/law.mu": mu, "body/law.C1": mu / 2} for mu in np.linspace(5e3, 20e3, 7)]
    sets.insert(3, {"body/law.mu": -1.0})  # a bad set: the law refuses a negative modulus
    table = fascia.sweep(cube_xml, sets, outputs=["monitor:probe", "step_count", ("top_z", _top_z)], steps=40,
                         n_workers=2, output_dir=tmp_path)
    assert len(table) == 8
    bad = table.iloc[3]
    assert "mu" in bad["error"] and "SceneError" in bad["error"]
    good = table.drop(index=3)
    assert good["error"].isna().all()
    assert (good["step_count"] == 40).all()
    # a stiffer body needs a larger force to hold the same displacement
    cols = [c for c in good.columns if c.startswith("probe.") and "reaction_z" in c]
    assert cols, list(good.columns)
    force = np.array([abs(v[-1]) for v in good[cols[0]]])
    assert np.all(np.diff(force) > 0)
    assert np.all(good["top_z"] < 0.1)


def _top_z(sim):
    return float(np.max(np.asarray(sim.state("state").x)[:, 2]))
