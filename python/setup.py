# The cffi extension lignum._lignum (lignum/_build.py); everything else is
# in pyproject.toml.
from setuptools import setup

setup(cffi_modules=["lignum/_build.py:ffibuilder"])
