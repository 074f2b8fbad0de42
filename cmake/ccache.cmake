# ccache when present: rebuilds on 2 cores are dominated by Eigen headers. The tests' precompiled
# headers (tests/CMakeLists.txt) are cached only with this sloppiness (ccache's manual,
# "Precompiled headers").
find_program(PBM_CCACHE ccache)
if(PBM_CCACHE)
  set(CMAKE_CXX_COMPILER_LAUNCHER ${CMAKE_COMMAND} -E env
                                  CCACHE_SLOPPINESS=pch_defines,time_macros ${PBM_CCACHE})
endif()
