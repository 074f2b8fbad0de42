# PBM_TSAN: ThreadSanitizer on every target, for the engine thread's test (tools/test runs it in
# build/tsan). Compile and link flags both: the runtime must be linked into each executable.
option(PBM_TSAN "Build with ThreadSanitizer (-fsanitize=thread)" OFF)
if(PBM_TSAN)
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
endif()

# PBM_ASAN: AddressSanitizer and UndefinedBehaviorSanitizer on every target, for hunting memory
# errors in the engine's preallocated scratch (build/asan).
option(PBM_ASAN "Build with AddressSanitizer and UBSan (-fsanitize=address,undefined)" OFF)
if(PBM_ASAN)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()
