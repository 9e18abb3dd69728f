"""The plugin is found by the lmp command and by the Python module without `plugin load`."""

from bonded_lattice import __version__
from helpers.decks import run_deck


def test_python_module_has_styles(lmp_instance):
    # None: every category (LAMMPS before 22 Jul 2025 requires the argument and ignores it)
    plugins = {tuple(p) for p in lmp_instance.available_plugins(None)}
    for style in [("pair", "lattice/bond"), ("fix", "lattice/viscous"), ("fix", "lattice/wall"),
                  ("compute", "lattice/bonds")]:
        assert style in plugins
    # `plugin list` shows the package version through the version command's name
    assert ("command", f"bonded_lattice/{__version__}") in plugins


def test_lmp_command_lists_version(tmp_path):
    res = run_deck("plugin list\n", tmp_path)
    assert res.returncode == 0, res.output
    assert f"command style plugin bonded_lattice/{__version__}" in res.output
    assert "pair style plugin lattice/bond" in res.output


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
