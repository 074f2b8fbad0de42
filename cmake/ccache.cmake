# ccache when present: rebuilds on 2 cores are dominated by Eigen headers.
find_program(PBM_CCACHE ccache)
if(PBM_CCACHE)
  set(CMAKE_CXX_COMPILER_LAUNCHER ${PBM_CCACHE})
endif()
