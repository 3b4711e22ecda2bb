# The shared tile render loop and the pixel-sample pipeline (below the integrators, which
# own their render loops and use this one by default).
snell_library(snell_render
  src/render/renderer.cpp
  src/render/camera_sample.cpp
  src/render/render_team.cpp
  src/render/team_pass.cpp
  src/render/mpi_team.cpp
  src/render/partial_film.cpp
)
target_link_libraries(snell_render PUBLIC snell_scene snell_sampler snell_camera snell_io snell_core TBB::tbb
                      PRIVATE OpenEXR::OpenEXR)
# Open MPI (issue 27): one frame over the ranks of an MPI job. Built whenever MPI is found;
# without it snell renders in one process as before (render/mpi_team.h).
find_package(MPI COMPONENTS CXX QUIET)
if(MPI_CXX_FOUND AND NOT SNELL_SANITIZE)
  target_link_libraries(snell_render PRIVATE MPI::MPI_CXX)
  target_compile_definitions(snell_render PRIVATE SNELL_HAVE_MPI)
  set(SNELL_HAVE_MPI ON)
endif()

snell_test(test_team_pass SOURCES tests/unit/test_team_pass.cpp LIBS snell_render)
