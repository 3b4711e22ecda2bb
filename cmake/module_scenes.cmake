# Scenes under scenes/: meshes made at build time, and a test that every scene renders.
#
# scenes/bunny_sphere needs the Stanford bunny, taken from the npm package `bunny` (pinned) and
# converted to scenes/bunny_sphere/bunny.obj (gitignored) by scripts/make_bunny_mesh.sh. Without
# node/npm (scripts/install-deps.sh installs them) or the registry, the build goes on and says
# so; scenes/glass_sphere is the same set-up with a cube. The caustic gallery (scenes/caustics)
# has its meshes and sky made by scripts/make_gallery_assets.js (node) the same way.
set(SNELL_BUNNY_VERSION 1.0.1)
find_program(SNELL_NODE node)
find_program(SNELL_NPM npm)
if(SNELL_NODE AND SNELL_NPM)
  set(_bunny_stamp ${PROJECT_BINARY_DIR}/npm/bunny-${SNELL_BUNNY_VERSION}.stamp)
  add_custom_command(
    OUTPUT ${_bunny_stamp}
    COMMAND bash ${PROJECT_SOURCE_DIR}/scripts/make_bunny_mesh.sh ${PROJECT_BINARY_DIR}/npm
            ${PROJECT_SOURCE_DIR}/scenes/bunny_sphere/bunny.obj ${SNELL_BUNNY_VERSION}
    COMMAND ${CMAKE_COMMAND} -E touch ${_bunny_stamp}
    DEPENDS ${PROJECT_SOURCE_DIR}/scripts/make_bunny_mesh.sh ${PROJECT_SOURCE_DIR}/scripts/bunny_to_obj.js
    COMMENT "scenes: Stanford bunny (npm bunny@${SNELL_BUNNY_VERSION}) -> scenes/bunny_sphere/bunny.obj"
    VERBATIM)
  # The caustic gallery's assets (scenes/caustics/meshes/, gitignored): the UV-sphere ball, the
  # pool's height field, the sky and, when the npm bunny is there, the smooth-normal bunny.
  # The files themselves are the outputs (not a stamp), so a deleted one is made again.
  set(_gallery_dir ${PROJECT_SOURCE_DIR}/scenes/caustics/meshes)
  set(_gallery_outputs ${_gallery_dir}/ball.obj ${_gallery_dir}/pool.obj ${_gallery_dir}/sky.hdr)
  add_custom_command(
    OUTPUT ${_gallery_outputs}
    COMMAND ${SNELL_NODE} ${PROJECT_SOURCE_DIR}/scripts/make_gallery_assets.js
            ${_gallery_dir} ${PROJECT_BINARY_DIR}/npm
    DEPENDS ${_bunny_stamp} ${PROJECT_SOURCE_DIR}/scripts/make_gallery_assets.js
    COMMENT "scenes: caustic gallery meshes and sky -> scenes/caustics/meshes/"
    VERBATIM)
  add_custom_target(scene_meshes ALL DEPENDS ${_bunny_stamp} ${_gallery_outputs})
else()
  message(STATUS "scenes: node/npm not found, scenes/bunny_sphere and the caustic gallery's meshes "
                 "are unavailable (scripts/install-deps.sh installs nodejs and npm); "
                 "scenes/glass_sphere has a cube instead")
endif()

if(SNELL_BUILD_TESTS AND NOT SNELL_SANITIZE)
  add_test(NAME scenes.render_all
           COMMAND bash ${PROJECT_SOURCE_DIR}/tests/scenes/test_scenes.sh $<TARGET_FILE:snell> ${PROJECT_SOURCE_DIR}/scenes)
  set_tests_properties(scenes.render_all PROPERTIES TIMEOUT 120)
endif()
