"""Builds the Python package chasles with CMake (docs/python.md).

build_ext configures this checkout into build-pip/cmake with the tests, benchmarks and fuzz
targets off and the Python module on, builds the extension (target chasles_python) and copies
it into the package. The interpreter running pip is the one the module is built for.
"""

import os
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE_DIR = os.path.dirname(os.path.abspath(__file__))
os.makedirs(os.path.join(SOURCE_DIR, "build-pip"), exist_ok=True)


class CMakeExtension(Extension):
    """An extension whose sources CMake compiles."""

    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    """Runs CMake and copies the module it builds to where setuptools expects it."""

    def build_extension(self, ext):
        build_dir = os.path.join(SOURCE_DIR, "build-pip", "cmake")
        os.makedirs(build_dir, exist_ok=True)
        subprocess.check_call([
            "cmake", "-S", SOURCE_DIR, "-B", build_dir,
            "-DCMAKE_BUILD_TYPE=Release",
            "-DCHASLES_BUILD_TESTS=OFF", "-DCHASLES_BUILD_BENCH=OFF", "-DCHASLES_FUZZ=OFF",
            "-DCHASLES_SANITIZE=OFF", "-DCHASLES_BUILD_PYTHON=ON",
            f"-DPython3_EXECUTABLE={sys.executable}",
        ])
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", "2")
        subprocess.check_call(["cmake", "--build", build_dir, "--target", "chasles_python",
                               "-j", jobs])
        built = os.path.join(build_dir, "python", "chasles")
        module = [f for f in os.listdir(built) if f.startswith("_chasles") and f.endswith(".so")]
        if not module:
            raise RuntimeError(f"CMake built no extension in {built} (is pybind11 installed?)")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        self.copy_file(os.path.join(built, module[0]), target)


setup(
    packages=["chasles"],
    package_dir={"chasles": "bindings/python/chasles"},
    ext_modules=[CMakeExtension("chasles._chasles")],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": "build-pip"}, "egg_info": {"egg_base": "build-pip"}},
    zip_safe=False,
)
