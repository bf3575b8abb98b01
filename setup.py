"""Builds the Python module for pip (pyproject.toml): the CMake target fitlib_python in
FITLIB_BUILD_DIR when set (a build tree that has it), else in build-pip/ of the source tree, then
packages <build>/python/fitlib (python/fitlib/*.py and _fitlib*.so) as the package fitlib."""
import os
import shutil
import subprocess
import sys

from setuptools import Distribution, setup
from setuptools.command.build_ext import build_ext

HERE = os.path.dirname(os.path.abspath(__file__))


class BuildWithCMake(build_ext):  # run because the distribution has an extension (below)
    def run(self):
        build = os.environ.get("FITLIB_BUILD_DIR")
        if not build:
            build = os.path.join(HERE, "build-pip")
            subprocess.check_call(["cmake", "-S", HERE, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                                   "-DFITLIB_TESTS=OFF", "-DFITLIB_BENCH=OFF", "-DFITLIB_PYTHON=ON",
                                   "-DPython_EXECUTABLE=" + sys.executable])
            subprocess.check_call(["cmake", "--build", build, "--target", "fitlib_python",
                                   "-j", os.environ.get("JOBS", "2")])
        package = os.path.join(build, "python", "fitlib")
        if not any(name.startswith("_fitlib") for name in os.listdir(package)):
            sys.exit(f"setup.py: no _fitlib extension in {package}: build the target fitlib_python")
        target = os.path.join(self.build_lib, "fitlib")
        shutil.rmtree(target, ignore_errors=True)
        shutil.copytree(package, target, ignore=shutil.ignore_patterns("__pycache__"))


class BinaryDistribution(Distribution):
    def has_ext_modules(self):  # a platform wheel: the package holds a compiled extension
        return True


setup(cmdclass={"build_ext": BuildWithCMake}, distclass=BinaryDistribution)
