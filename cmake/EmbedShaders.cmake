# Embeds text files into a generated C++ source as raw string literals, keyed by their path
# relative to ROOT, so the binary carries its shaders (and style presets) and an edit rebuilds
# only that source.
#   vsil_embed_files(OUT_CPP <file> ROOT <dir> FILES <files> NAMESPACE <ns> FUNCTION <name>
#                    LIST_FUNCTION <name> [COMMENT <text>])
# defines `std::string_view <ns>::<FUNCTION>(std::string_view path)` (throws
# std::invalid_argument for a path it does not hold) and
# `std::vector<std::string_view> <ns>::<LIST_FUNCTION>()`.
function(vsil_embed_files)
  cmake_parse_arguments(ARG "" "OUT_CPP;ROOT;NAMESPACE;FUNCTION;LIST_FUNCTION;COMMENT" "FILES"
                        ${ARGN})
  add_custom_command(
    OUTPUT ${ARG_OUT_CPP}
    COMMAND ${CMAKE_COMMAND} -DOUT=${ARG_OUT_CPP} -DROOT=${ARG_ROOT} "-DFILES=${ARG_FILES}"
            -DNAMESPACE=${ARG_NAMESPACE} -DFUNCTION=${ARG_FUNCTION}
            -DLIST_FUNCTION=${ARG_LIST_FUNCTION}
            -P ${PROJECT_SOURCE_DIR}/cmake/EmbedShadersScript.cmake
    DEPENDS ${ARG_FILES} ${PROJECT_SOURCE_DIR}/cmake/EmbedShadersScript.cmake
    COMMENT "${ARG_COMMENT}"
    VERBATIM)
endfunction()

# The GLSL under slicing/: vsil::gl::embeddedShaderSource(path), embeddedShaderPaths().
#   vsil_embed_shaders(OUT_CPP <file> ROOT <dir> FILES <glsl files>)
function(vsil_embed_shaders)
  cmake_parse_arguments(ARG "" "OUT_CPP;ROOT" "FILES" ${ARGN})
  vsil_embed_files(OUT_CPP ${ARG_OUT_CPP} ROOT ${ARG_ROOT} FILES ${ARG_FILES} NAMESPACE vsil::gl
                   FUNCTION embeddedShaderSource LIST_FUNCTION embeddedShaderPaths
                   COMMENT "Embedding GLSL shaders")
endfunction()
