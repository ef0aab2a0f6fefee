# isolux-cli's sources besides main.cpp: the subcommands and the flags they
# share. Listed once, for isolux-cli (app/) and its fuzz target (tests/fuzz/).
set(ISOLUX_CLI_SOURCES
  ${PROJECT_SOURCE_DIR}/app/cli/args.cpp
  ${PROJECT_SOURCE_DIR}/app/cli/render.cpp
  ${PROJECT_SOURCE_DIR}/app/cli/check_tileset.cpp
  ${PROJECT_SOURCE_DIR}/app/cli/sweep.cpp
  ${PROJECT_SOURCE_DIR}/app/cli/sweep_chart.cpp
  ${PROJECT_SOURCE_DIR}/app/cli/contact_sheet.cpp
  ${PROJECT_SOURCE_DIR}/app/cli/export_tiled.cpp
  ${PROJECT_SOURCE_DIR}/app/cli/normals.cpp)
