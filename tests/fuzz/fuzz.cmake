# The scene fuzzer, built with clang's libFuzzer and sanitizers, included from the top-level
# CMakeLists.txt (the embedded sources are generated there) when scripts/fuzz.sh configures a
# separate build tree with -DDEPTHPREC_FUZZ=ON and CXX=clang++).
set(FUZZ_FLAGS -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -g -O1)
add_library(scene_fuzz_core STATIC
  ${EMBEDDED_CPP}
  ${PROJECT_SOURCE_DIR}/host/runtime/expand_embedded.cpp
  ${PROJECT_SOURCE_DIR}/host/model/scene.cpp
  ${PROJECT_SOURCE_DIR}/host/model/technique.cpp
  ${PROJECT_SOURCE_DIR}/host/model/storage_format.cpp
  ${PROJECT_SOURCE_DIR}/host/runtime/kernel_variant.cpp
  ${PROJECT_SOURCE_DIR}/host/runtime/opencl_runtime.cpp
)
target_include_directories(scene_fuzz_core PUBLIC ${PROJECT_SOURCE_DIR})
target_compile_options(scene_fuzz_core PRIVATE ${FUZZ_FLAGS})
target_compile_definitions(scene_fuzz_core PUBLIC CL_TARGET_OPENCL_VERSION=120)
target_link_libraries(scene_fuzz_core PUBLIC fmt::fmt nlohmann_json::nlohmann_json OpenCL::OpenCL)
add_executable(scene_fuzzer ${PROJECT_SOURCE_DIR}/tests/fuzz/scene_fuzzer.cpp)
set_target_properties(scene_fuzzer PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests/fuzz)
target_compile_options(scene_fuzzer PRIVATE ${FUZZ_FLAGS})
target_link_options(scene_fuzzer PRIVATE -fsanitize=fuzzer,address,undefined)
target_link_libraries(scene_fuzzer PRIVATE scene_fuzz_core)
