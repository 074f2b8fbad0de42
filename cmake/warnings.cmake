# pbm_warnings(target): the warning set every project target builds with.
add_library(pbm_warnings INTERFACE)
target_compile_options(pbm_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                                              -Wno-maybe-uninitialized)
if(PBM_WERROR)
  target_compile_options(pbm_warnings INTERFACE -Werror)
endif()
