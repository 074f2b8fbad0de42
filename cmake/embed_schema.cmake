# Writes OUT_CPP: scene_schema_text() returning scenes/scene.schema.json, so the studio's
# inspector shows each field's unit and range without reading files at run time.
file(READ "${SCHEMA}" text)
file(WRITE "${OUT_CPP}.tmp"
     "// Generated from scenes/scene.schema.json by cmake/embed_schema.cmake; do not edit.\n"
     "namespace pbm {\nconst char* scene_schema_text() {\n  return R\"pbm_schema(${text})pbm_schema\";\n}\n"
     "}  // namespace pbm\n")
file(COPY_FILE "${OUT_CPP}.tmp" "${OUT_CPP}" ONLY_IF_DIFFERENT)
