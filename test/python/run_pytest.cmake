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
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env LIGNUM_BUILD_DIR=${BUILD_DIR}
          ${venv}/bin/python -m pip install --quiet --no-build-isolation --no-deps
          --no-cache-dir --force-reinstall ${SOURCE_DIR}/python
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pip install ${SOURCE_DIR}/python failed (${rc})")
endif()
# pip builds in the source tree: leave it clean
file(REMOVE_RECURSE ${SOURCE_DIR}/python/build ${SOURCE_DIR}/python/lignum.egg-info)
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env LIGNUM_HEAVY_TOP_REF=${HEAVY_TOP_REF}
          LIGNUM_SOURCE_DIR=${SOURCE_DIR} MPLBACKEND=Agg
          ${venv}/bin/python -m pytest -q -p no:cacheprovider ${SOURCE_DIR}/test/python
  WORKING_DIRECTORY ${BUILD_DIR}
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pytest failed (${rc})")
endif()
