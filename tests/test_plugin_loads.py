"""The plugin is found by the lmp command and by the Python module without `plugin load`."""

from bonded_lattice import __version__


def test_python_module_has_styles(lmp_instance):
    plugins = {tuple(p) for p in lmp_instance.available_plugins()}
    for style in [("pair", "lattice/bond"), ("fix", "lattice/viscous"), ("fix", "lattice/wall"),
                  ("compute", "lattice/bonds")]:
        assert style in plugins
    # `plugin list` shows the package version through the version command's name
    assert ("command", f"bonded_lattice/{__version__}") in plugins


def test_lmp_command_lists_version(tmp_path):
    from conftest import run_deck

    res = run_deck("plugin list\n", tmp_path)
    assert res.returncode == 0, res.output
    assert f"command style plugin bonded_lattice/{__version__}" in res.output
    assert "pair style plugin lattice/bond" in res.output
