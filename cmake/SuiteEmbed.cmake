# suite_embed_text(<target> <symbol> <file>): compiles the text of <file> into <target> as
#   namespace suite::embedded { extern const char* const <symbol>; }
# so an executable carries its default scene and still runs with no files beside it.
function(suite_embed_text target symbol file)
  set(out ${CMAKE_CURRENT_BINARY_DIR}/embedded/${symbol}.cpp)
  add_custom_command(OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DIN=${file} -DOUT=${out} -DSYMBOL=${symbol}
            -P ${PROJECT_SOURCE_DIR}/cmake/SuiteEmbedScript.cmake
    DEPENDS ${file} ${PROJECT_SOURCE_DIR}/cmake/SuiteEmbedScript.cmake
    COMMENT "embedding ${file}")
  target_sources(${target} PRIVATE ${out})
endfunction()
