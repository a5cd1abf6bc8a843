# Precompiled headers for the heavy header-only libraries (CLI11 takes ~10 s to parse per file,
# nlohmann/json and toml++ ~3 s, Catch2 and OpenCV's core ~2 s), once per target instead of once
# per file: the Release and sanitizer builds of the test command spend most of their time there.
# TILEJET_PCH=OFF builds without them (e.g. to check that every file includes what it uses).
option(TILEJET_PCH "precompile heavy third-party headers once per target" ON)

# tilejet_precompile(target <header> ...): each header as an include would name it, e.g.
# "<CLI/CLI.hpp>"; the target must already be able to find it.
function(tilejet_precompile target)
    if(TILEJET_PCH)
        target_precompile_headers(${target} PRIVATE ${ARGN})
    endif()
endfunction()
