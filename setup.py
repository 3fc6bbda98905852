"""Builds the wheel of `pip install .` with the project's CMake (pyproject.toml says how to call it).

The extension and the libtorch plugin are built by CMake in build-pip/ (CROPSIGHT_PIP_BUILD_DIR to
change it; tests, benchmarks, examples and ROS off), then copied into the package with the shipped
presets and models: a wheel holds only its package folder, so the plugin goes to cropsight/lib/ and
the data to cropsight/share/cropsight/, and _layout.py says that the prefix is the package itself
(python/cropsight/_plugin_paths.py finds both through it, as in an install).
"""
import glob
import os
import shutil
import subprocess

from setuptools import Distribution, setup
from setuptools.command.build_py import build_py

HERE = os.path.dirname(os.path.abspath(__file__))
# CMake's tree and setuptools' own build and egg-info folders, all in one place out of the sources.
BUILD = os.path.join(HERE, os.environ.get("CROPSIGHT_PIP_BUILD_DIR", "build-pip"))


class BuildWithCMake(build_py):
    def run(self):
        super().run()  # the package's .py files
        build = BUILD
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", "2")
        env = dict(os.environ, CCACHE_BASEDIR=HERE, CCACHE_NOHASHDIR="1")
        generator = ["-G", "Ninja"] if shutil.which("ninja") else []
        subprocess.run(["cmake", "-S", HERE, "-B", build, *generator, "-DCMAKE_BUILD_TYPE=Release",
                        "-DCROPSIGHT_BUILD_TESTS=OFF", "-DCROPSIGHT_BUILD_BENCH=OFF",
                        "-DCROPSIGHT_BUILD_EXAMPLES=OFF", "-DCROPSIGHT_ROS=OFF"], check=True, env=env)
        subprocess.run(["cmake", "--build", build, "-j", jobs, "--target", "cropsight_python", "cropsight_nn_torch"],
                       check=True, env=env)
        package = os.path.join(self.build_lib, "cropsight")
        for f in glob.glob(os.path.join(HERE, "python", "cropsight", "*.pyi")) + \
                [os.path.join(HERE, "python", "cropsight", "py.typed")]:
            shutil.copy2(f, package)
        for f in glob.glob(os.path.join(build, "python", "cropsight", "_cropsight*.so")):
            shutil.copy2(f, package)
        os.makedirs(os.path.join(package, "lib"), exist_ok=True)
        shutil.copy2(os.path.join(build, "lib", "libcropsight_nn_torch.so"), os.path.join(package, "lib"))
        for d in ("configs", "models"):
            target = os.path.join(package, "share", "cropsight", d)
            shutil.rmtree(target, ignore_errors=True)
            shutil.copytree(os.path.join(HERE, d), target)
        with open(os.path.join(package, "_layout.py"), "w") as f:
            f.write("# Written by setup.py: a wheel holds the plugin and data inside the package.\n"
                    "PREFIX_FROM_PACKAGE = '.'\n")


class BinaryDistribution(Distribution):
    def has_ext_modules(self):  # the wheel holds a compiled extension: a platform wheel
        return True


setup(
    packages=["cropsight"],
    package_dir={"": "python"},
    cmdclass={"build_py": BuildWithCMake},
    distclass=BinaryDistribution,
    # setuptools' default build/ is the CMake build tree of make build.
    options={"build": {"build_base": os.path.join(BUILD, "setuptools")}, "egg_info": {"egg_base": BUILD}},
)
