"""pydicom's own test files (Debian's python3-pydicom ships them): DICOM written by many tools
in every encoding (implicit and explicit VR, big endian, no File Meta, bad VRs, private and UN
sequences, RLE, JPEG, JPEG 2000, deflate, truncated files). `vsil info` must read each or refuse
it with a one-line error, exit 2, and the check of declared element lengths that keeps GDCM from
allocating beyond a file (src/io/dicom_reader.cpp overlongElement) must name only the file that
is truncated inside an element before its pixel data.

Run by ctest (tests/CMakeLists.txt, io.reference_writers) with VSIL_BINARY set."""

import os
import shutil
import subprocess

import pytest

pydicom = pytest.importorskip("pydicom", reason="pydicom (python3-pydicom) is not installed")
FOLDER = os.path.join(os.path.dirname(pydicom.__file__), "data", "test_files")
FILES = sorted(f for f in os.listdir(FOLDER) if f.endswith(".dcm")) if os.path.isdir(FOLDER) else []
VSIL = os.environ.get("VSIL_BINARY", "vsil")
# Truncated inside an element before its pixel data: the length check names it.
CUT_BEFORE_PIXELS = {"rtplan_truncated.dcm"}


def test_the_test_files_are_there():
    assert len(FILES) >= 50, "pydicom's test files are missing from " + FOLDER


@pytest.mark.parametrize("name", FILES)
def test_a_pydicom_test_file_reads_or_gets_one_line(tmp_path, name):
    shutil.copy(os.path.join(FOLDER, name), tmp_path / name)  # alone in its folder
    result = subprocess.run([VSIL, "info", str(tmp_path / name)], capture_output=True, text=True,
                            timeout=120)
    lines = [line for line in result.stderr.splitlines() if not line.startswith("vsil: warning:")]
    if result.returncode == 0:
        assert result.stdout.startswith("source"), result.stdout
        return
    assert result.returncode == 2, result.stderr
    assert len(lines) == 1 and lines[0].startswith("vsil: "), result.stderr
    assert ("declares" in lines[0]) == (name in CUT_BEFORE_PIXELS), lines[0]
