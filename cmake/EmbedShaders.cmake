# Shaders are embedded into the binary at build time so curette runs from anywhere.
# curette_embed_shaders(<target> <source-dir> <files...>) generates one C++ file holding every
# shader as a raw string, regenerated whenever a shader changes.

set(CURETTE_EMBED_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/embed_shaders_run.cmake)

function(curette_embed_shaders target source_dir)
  set(output ${CMAKE_CURRENT_BINARY_DIR}/embedded_shaders.cpp)
  set(inputs)
  foreach(f IN LISTS ARGN)
    list(APPEND inputs ${source_dir}/${f})
  endforeach()
  string(REPLACE ";" "|" names "${ARGN}")
  add_custom_command(
    OUTPUT ${output}
    COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${source_dir} -DNAMES=${names} -DOUTPUT=${output}
            -P ${CURETTE_EMBED_SCRIPT}
    DEPENDS ${inputs} ${CURETTE_EMBED_SCRIPT}
    COMMENT "Embedding ${target} shaders"
    VERBATIM)
  target_sources(${target} PRIVATE ${output})
endfunction()
