# The manifold solver (paper Sec. 3): vertices, half-vector constraints, the block-tridiagonal
# solve, the walk and the chain Jacobians. Independent of every integrator.
snell_library(snell_manifold
  src/manifold/manifold_vertex.cpp
  src/manifold/constraints.cpp
  src/manifold/block_tridiagonal.cpp
  src/manifold/manifold_walk.cpp
  src/manifold/generalized_geometry.cpp
  src/manifold/seed_path.cpp
  src/manifold/mnee.cpp
  src/manifold/mnee_settings.cpp
  src/manifold/light_point.cpp
  src/manifold/walk_statistics.cpp
  src/manifold/walk_counters.cpp
  src/manifold/solution_set.cpp
  src/manifold/half_vectors.cpp
  src/manifold/manifold_technique.cpp
  src/manifold/estimator_base.cpp
  src/manifold/straight_seed_estimator.cpp
  src/manifold/multi_solution_estimator.cpp
  src/manifold/fallback_estimator.cpp
  src/manifold/keyed_trials_estimator.cpp
  src/manifold/surface_seed.cpp
  src/manifold/caster_choice.cpp
  src/manifold/exterior_reflection.cpp
)
target_link_libraries(snell_manifold PUBLIC snell_scene snell_geometry snell_bsdf snell_light snell_core
                      nlohmann_json::nlohmann_json)

snell_test(test_manifold
  SOURCES tests/manifold/test_constraints.cpp tests/manifold/test_walk.cpp tests/manifold/test_solution_set.cpp
          tests/manifold/test_half_vectors.cpp
  LIBS snell_manifold)
