"""Builds the extension vsil._vsil with the project's own CMake (pyproject.toml says why
setuptools): configure once into build-pip/ (kept, so a second `pip install .` rebuilds only what
changed), build the one target vsil_python, copy the extension and its generated stub into the
wheel. Only the module: no tests, micro-benchmarks or command-line tool.

Environment: CMAKE_ARGS (more cmake arguments, e.g. -DVSIL_OSMESA=OFF), CMAKE_BUILD_PARALLEL_LEVEL
(jobs; default: the CPUs this process may use), VSIL_PIP_BUILD_DIR (default build-pip)."""
import hashlib
import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def project_version():
    """The version in the top-level project() call: one place for CMake, the module and pip."""
    text = (ROOT / "CMakeLists.txt").read_text()
    match = re.search(r"project\(\s*vsil\s+VERSION\s+([0-9][0-9.]*)", text)
    if not match:
        sys.exit("setup.py: no `project(vsil VERSION ...)` in CMakeLists.txt")
    return match.group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        # One CMake tree per base interpreter: the extension's ABI and include paths are its.
        interpreter = f"{sys.implementation.cache_tag}-{sys.base_prefix}"
        tag = hashlib.sha1(interpreter.encode()).hexdigest()[:8]
        build_dir = Path(os.environ.get("VSIL_PIP_BUILD_DIR", ROOT / "build-pip")) / (
            f"{sys.implementation.cache_tag}-{tag}")
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build_dir),
            "-DCMAKE_BUILD_TYPE=RelWithDebInfo",  # what the CLI is built as: the same pixels
            # One translation unit per target: about half the time of a first build, which is
            # what an install is.
            "-DCMAKE_UNITY_BUILD=ON",
            "-DVSIL_BUILD_TESTS=OFF", "-DVSIL_BUILD_BENCH=OFF", "-DVSIL_PYTHON=ON",
            # The interpreter running pip (a venv's python): its headers, its extension suffix.
            f"-DPython3_EXECUTABLE={sys.executable}",
        ]
        try:  # pybind11 from PyPI in an isolated build; Debian's pybind11-dev is found otherwise
            import pybind11
            configure.append(f"-Dpybind11_DIR={pybind11.get_cmake_dir()}")
        except ImportError:
            pass
        # ccache where installed: reinstalls and other checkouts reuse every object compiled
        # before (a reinstall after a small change takes seconds, not minutes).
        if shutil.which("ccache"):
            configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
        configure += shlex.split(os.environ.get("CMAKE_ARGS", ""))
        # Every CPU this process may use: the build is most of an install's time.
        cpus = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(cpus or 1)
        if not shutil.which("cmake"):
            sys.exit("setup.py: vsil builds with CMake >= 3.25, which is not on the PATH: "
                     "apt-get install cmake (scripts/bootstrap.sh installs every dependency)")
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "vsil_python", "-j", jobs],
                       check=True)

        package = build_dir / "python" / "vsil"
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        built = sorted(package.glob("_vsil*.so"))
        if len(built) != 1:
            sys.exit(f"setup.py: expected one _vsil*.so in {package}, found {built}")
        shutil.copyfile(built[0], target)
        shutil.copyfile(package / "__init__.pyi", target.parent / "__init__.pyi")
        # The plugins the extension loads from beside it: video (Renderer.animate(video=...)) and
        # DICOM (a DICOM volume).
        for plugin in ("libvsil_video.so", "libvsil_dicom.so"):
            shutil.copyfile(package / plugin, target.parent / plugin)


setup(
    version=project_version(),
    ext_modules=[Extension("vsil._vsil", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own folders (build/lib..., build/bdist...) beside the CMake ones, not in the
    # developer's build/.
    options={"build": {"build_base": str(ROOT / "build-pip" / "setuptools")}},
)
