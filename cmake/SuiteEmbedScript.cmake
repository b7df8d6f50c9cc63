# cmake -P helper of suite_embed_text(): IN, OUT, SYMBOL.
file(READ ${IN} text)
if(text MATCHES "\\)SUITE_EMBED\"")
  message(FATAL_ERROR "${IN} contains the raw-string delimiter )SUITE_EMBED\"")
endif()
file(WRITE ${OUT} "namespace suite::embedded {\nextern const char* const ${SYMBOL};\nconst char* const ${SYMBOL} = R\"SUITE_EMBED(${text})SUITE_EMBED\";\n}\n")
