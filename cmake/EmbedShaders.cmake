# Embeds GLSL files into a generated C++ source as raw string literals, so the binary carries its
# shaders and a shader edit rebuilds only that source.
#   vsil_embed_shaders(OUT_CPP <file> NAMESPACE <ns> FILES <glsl files>)
function(vsil_embed_shaders)
  cmake_parse_arguments(ARG "" "OUT_CPP" "FILES" ${ARGN})
  add_custom_command(
    OUTPUT ${ARG_OUT_CPP}
    COMMAND ${CMAKE_COMMAND} -DOUT=${ARG_OUT_CPP} "-DFILES=${ARG_FILES}"
            -P ${PROJECT_SOURCE_DIR}/cmake/EmbedShadersScript.cmake
    DEPENDS ${ARG_FILES} ${PROJECT_SOURCE_DIR}/cmake/EmbedShadersScript.cmake
    COMMENT "Embedding GLSL shaders"
    VERBATIM)
endfunction()
