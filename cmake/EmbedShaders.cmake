# Embeds GLSL files into a generated C++ source as raw string literals, keyed by their path
# relative to ROOT, so the binary carries its shaders and a shader edit rebuilds only that source.
#   vsil_embed_shaders(OUT_CPP <file> ROOT <dir> FILES <glsl files>)
function(vsil_embed_shaders)
  cmake_parse_arguments(ARG "" "OUT_CPP;ROOT" "FILES" ${ARGN})
  add_custom_command(
    OUTPUT ${ARG_OUT_CPP}
    COMMAND ${CMAKE_COMMAND} -DOUT=${ARG_OUT_CPP} -DROOT=${ARG_ROOT} "-DFILES=${ARG_FILES}"
            -P ${PROJECT_SOURCE_DIR}/cmake/EmbedShadersScript.cmake
    DEPENDS ${ARG_FILES} ${PROJECT_SOURCE_DIR}/cmake/EmbedShadersScript.cmake
    COMMENT "Embedding GLSL shaders"
    VERBATIM)
endfunction()
