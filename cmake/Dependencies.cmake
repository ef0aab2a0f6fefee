# Every dependency is a Debian 12 package (see scripts/deps.sh).
find_package(nlohmann_json 3 CONFIG REQUIRED)
find_package(Threads REQUIRED)
# 3D math (the sprites' solids and the 3D reference): GLM, header-only.
find_package(glm CONFIG REQUIRED)

# OpenImageIO 2.4's imported target lists /usr/include/opencv4, which Debian
# does not ship unless OpenCV is installed: drop it so configure succeeds.
find_package(OpenImageIO CONFIG REQUIRED)
include(cmake/FixOpenImageIO.cmake)

# Tiled maps: XML, and the layer compressions TMX allows.
find_package(pugixml CONFIG REQUIRED)
find_package(ZLIB REQUIRED)
find_package(zstd CONFIG REQUIRED)
