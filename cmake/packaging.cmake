# The Debian package of the install rules (scripts/package.sh builds it;
# scripts/check_package.sh installs it into a clean Debian 12 root).
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME colmap-gcn)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "colmap-gcn maintainers <colmap-gcn@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
  "COLMAP image-pair selection with a graph neural network")
set(CPACK_PACKAGE_DESCRIPTION
  "colmap-gcn chooses which image pairs COLMAP matches (Yan et al., Image \
Retrieval for SfM via GCN) and runs COLMAP's own matcher on them. It installs \
the command colmap-gcn (COLMAP's commands plus gcn_matcher, gcn_reconstructor \
and the other gcn_* commands), the default model and a demo.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
# The real COLMAP (every non-gcn command is handed to it) and the runtime
# libraries the front end links, derived by dpkg-shlibdeps.
set(CPACK_DEBIAN_PACKAGE_DEPENDS "colmap (>= 3.8)")
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_STRIP_FILES ON)
include(CPack)
