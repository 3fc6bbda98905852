"""The package points the library at its own prefix's plugin and data folder, as the CLI finds them
beside its program, and leaves a user's CROPSIGHT_NN_BACKEND / CROPSIGHT_DATA_DIR alone."""
import os
import subprocess
import sys

import cropsight as cs


def run_python(code, **env):
    full = {k: v for k, v in os.environ.items() if k not in ("CROPSIGHT_NN_BACKEND", "CROPSIGHT_DATA_DIR")}
    full.update(env)
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=full)


def test_the_prefix_plugin_and_data_are_used():
    done = run_python("import os, cropsight; print(os.environ['CROPSIGHT_NN_BACKEND']); "
                      "print(os.environ['CROPSIGHT_DATA_DIR'])")
    assert done.returncode == 0, done.stderr
    plugin, data = done.stdout.split()
    assert os.path.isfile(plugin) and plugin.endswith("lib/libcropsight_nn_torch.so")
    assert os.path.isdir(os.path.join(data, "models")) and os.path.isdir(os.path.join(data, "configs"))
    assert os.path.dirname(os.path.dirname(plugin)) == os.path.dirname(os.path.dirname(data))  # one prefix


def test_a_users_plugin_path_is_kept_and_named_in_the_error(tmp_path):
    missing = str(tmp_path / "libnothing.so")
    code = ("import cropsight as cs\n"
            "try:\n"
            "    cs.grape.Pipeline(model='grape-pointresnet', threads=1)\n"
            "except cs.Error as e:\n"
            "    print(e)\n")
    done = run_python(code, CROPSIGHT_NN_BACKEND=missing)
    assert done.returncode == 0, done.stderr
    line = done.stdout.strip()
    assert "\n" not in line and missing in line and "CROPSIGHT_NN_BACKEND" in line
