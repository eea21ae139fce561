# cmake -DSRC=<gsse source> -DBIN=<build dir> -DCXX=<clang++> -P build_fuzzers.cmake
# Configures and builds tests/io/fuzz with clang, one job (the machine is shared).
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SRC}/tests/io/fuzz -B ${BIN} -G Ninja -DCMAKE_BUILD_TYPE=Release
                        -DCMAKE_CXX_COMPILER=${CXX} -DGSSE_SOURCE_DIR=${SRC}
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the fuzz targets failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BIN} -j1 RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the fuzz targets failed")
endif()
