# lld when present: the suite links about a hundred executables against the static engine, and
# one of them (tests/test_balloons) links in about 2 s with lld against 11 s with GNU ld.
include(CheckLinkerFlag)
check_linker_flag(CXX -fuse-ld=lld PBM_HAS_LLD)
if(PBM_HAS_LLD)
  add_link_options(-fuse-ld=lld)
endif()
