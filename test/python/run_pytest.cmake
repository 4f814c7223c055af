# ctest -R python_pytest: install python/ into BUILD_DIR/python-venv (a venv
# with the system's numpy, cffi, setuptools, pytest: nothing downloaded),
# built against the library in BUILD_DIR, then run test/python with pytest.
set(venv ${BUILD_DIR}/python-venv)
if(NOT EXISTS ${venv}/bin/python)
  execute_process(COMMAND ${PYTHON} -m venv --system-site-packages ${venv}
                  RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "python -m venv ${venv} failed (${rc})")
  endif()
endif()
# pip builds in the directory it is given: build from a fresh copy in the
# build tree, so that the source tree stays clean and no object of another
# build tree is reused
set(pkg ${BUILD_DIR}/python-pkg)
file(REMOVE_RECURSE ${pkg})
file(COPY ${SOURCE_DIR}/python/ DESTINATION ${pkg}
     PATTERN build EXCLUDE PATTERN *.egg-info EXCLUDE PATTERN __pycache__ EXCLUDE
     PATTERN _lignum.* EXCLUDE)
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env LIGNUM_BUILD_DIR=${BUILD_DIR}
          ${venv}/bin/python -m pip install --quiet --no-build-isolation --no-deps
          --no-cache-dir --force-reinstall ${pkg}
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pip install ${pkg} (a copy of ${SOURCE_DIR}/python) failed (${rc})")
endif()
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env LIGNUM_HEAVY_TOP_REF=${HEAVY_TOP_REF}
          LIGNUM_PLANAR_REF=${PLANAR_REF}
          LIGNUM_SOURCE_DIR=${SOURCE_DIR} MPLBACKEND=Agg
          ${venv}/bin/python -m pytest -q -p no:cacheprovider ${SOURCE_DIR}/test/python
  WORKING_DIRECTORY ${BUILD_DIR}
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pytest failed (${rc})")
endif()
