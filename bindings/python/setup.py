"""setuptools entry point: everything is declared in pyproject.toml except the cffi
extension, which cffi's setuptools integration adds from progsim_build.py."""
from setuptools import setup

setup(
    cffi_modules=["progsim_build.py:ffibuilder"],
    # pip builds in this folder, and build_ext would reuse a previous build whose C source is
    # unchanged, keeping a stale library path (PROGSIM_LIB_DIR) in it: always relink.
    options={"build_ext": {"force": True}},
)
