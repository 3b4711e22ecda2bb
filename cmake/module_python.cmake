# The `snell` Python module (issue 28, docs/python.md): the package python/snell/ (pure Python:
# the API, its docstrings and types) over the extension _snell (python/src/, pybind11), which
# runs the same code as the command line (snell_commands). Both land in
# ${PROJECT_BINARY_DIR}/python/snell, so `PYTHONPATH=build-release/python python3` imports it
# from the build tree; `cmake --install` puts the package into SNELL_PYTHON_INSTALL_DIR.
if(NOT SNELL_BUILD_PYTHON OR SNELL_SANITIZE)
  return()
endif()

# Debian's interpreter, the one python3-numpy and python3-pytest install into, unless told
# otherwise (-DPython_EXECUTABLE=...): a python3 earlier on PATH (pyenv, conda) may lack them.
if(NOT DEFINED Python_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python_EXECUTABLE /usr/bin/python3)
endif()
find_package(Python 3 REQUIRED COMPONENTS Interpreter Development.Module)
set(PYBIND11_FINDPYTHON ON)
find_package(pybind11 2.10 CONFIG REQUIRED)

pybind11_add_module(_snell MODULE
  python/src/module.cpp
  python/src/py_scene.cpp
  python/src/py_film.cpp
  python/src/render_call.cpp
  python/src/py_images.cpp
  python/src/py_compare.cpp
  python/src/py_json.cpp)
target_link_libraries(_snell PRIVATE snell_commands PkgConfig::OIIO)
target_compile_options(_snell PRIVATE ${SNELL_WARNINGS})
set(SNELL_PYTHON_DIR ${PROJECT_BINARY_DIR}/python)
set_target_properties(_snell PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${SNELL_PYTHON_DIR}/snell)

# The pure-Python part, copied beside the extension whenever it changes.
set(SNELL_PY_FILES __init__.py _image.py _scene.py py.typed)
set(SNELL_PY_OUTPUTS)
foreach(f ${SNELL_PY_FILES})
  add_custom_command(OUTPUT ${SNELL_PYTHON_DIR}/snell/${f}
                     COMMAND ${CMAKE_COMMAND} -E copy_if_different ${PROJECT_SOURCE_DIR}/python/snell/${f}
                             ${SNELL_PYTHON_DIR}/snell/${f}
                     DEPENDS ${PROJECT_SOURCE_DIR}/python/snell/${f})
  list(APPEND SNELL_PY_OUTPUTS ${SNELL_PYTHON_DIR}/snell/${f})
endforeach()
add_custom_target(snell_python ALL DEPENDS _snell ${SNELL_PY_OUTPUTS})

# Debian's place for packages installed under /usr/local (on sys.path of /usr/bin/python3).
set(SNELL_PYTHON_INSTALL_DIR lib/python3/dist-packages CACHE STRING
    "where `cmake --install` puts the snell package, relative to CMAKE_INSTALL_PREFIX")
install(TARGETS _snell LIBRARY DESTINATION ${SNELL_PYTHON_INSTALL_DIR}/snell COMPONENT python)
list(TRANSFORM SNELL_PY_FILES PREPEND ${PROJECT_SOURCE_DIR}/python/snell/ OUTPUT_VARIABLE SNELL_PY_SOURCES)
install(FILES ${SNELL_PY_SOURCES} DESTINATION ${SNELL_PYTHON_INSTALL_DIR}/snell COMPONENT python)

# pytest (tests/python/), against the build tree's package and the same build's `snell`.
if(SNELL_BUILD_TESTS)
  add_test(NAME python.api
           COMMAND ${Python_EXECUTABLE} -m pytest -q -p no:cacheprovider ${PROJECT_SOURCE_DIR}/tests/python)
  set_tests_properties(python.api PROPERTIES TIMEOUT 600
    ENVIRONMENT "PYTHONPATH=${SNELL_PYTHON_DIR};SNELL_BIN=$<TARGET_FILE:snell>;SNELL_SOURCE_DIR=${PROJECT_SOURCE_DIR};PYTHONDONTWRITEBYTECODE=1")
  add_dependencies(snell_test_suite snell_python)
  add_test(NAME python.install COMMAND bash ${PROJECT_SOURCE_DIR}/tests/python/test_install.sh ${PROJECT_BINARY_DIR}
                                       ${Python_EXECUTABLE} ${PROJECT_SOURCE_DIR})
  set_tests_properties(python.install PROPERTIES TIMEOUT 120)
endif()
