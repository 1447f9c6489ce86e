# The libFuzzer targets, built with clang's libFuzzer and sanitizers, included from the top-level
# CMakeLists.txt (after depthprec_core is defined, whose sources they reuse) when scripts/fuzz.sh
# configures a separate build tree with -DDEPTHPREC_FUZZ=ON and CXX=clang++:
#   scene_fuzzer    scene files (the parser and validator)
#   journal_fuzzer  row journals as --resume reads them
#   shard_fuzzer    JSON outputs as merge and compare read them
set(FUZZ_FLAGS -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -g -O1)
get_target_property(FUZZ_CORE_SOURCES depthprec_core SOURCES)
add_library(fuzz_core STATIC ${FUZZ_CORE_SOURCES})
target_include_directories(fuzz_core PUBLIC ${PROJECT_SOURCE_DIR})
target_compile_options(fuzz_core PRIVATE ${FUZZ_FLAGS})
target_compile_definitions(fuzz_core PUBLIC CL_TARGET_OPENCL_VERSION=120)
target_link_libraries(fuzz_core PUBLIC OpenCL::OpenCL fmt::fmt nlohmann_json::nlohmann_json glm::glm
                                       Threads::Threads PkgConfig::EPOXY)
foreach(target scene journal shard)
  add_executable(${target}_fuzzer ${PROJECT_SOURCE_DIR}/tests/fuzz/${target}_fuzzer.cpp)
  set_target_properties(${target}_fuzzer PROPERTIES
                        RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests/fuzz)
  target_compile_options(${target}_fuzzer PRIVATE ${FUZZ_FLAGS})
  target_link_options(${target}_fuzzer PRIVATE -fsanitize=fuzzer,address,undefined)
  target_link_libraries(${target}_fuzzer PRIVATE fuzz_core)
endforeach()
