# orocos-kdl and kdl_parser from the distribution: the peer that tests and benchmarks compare
# against. kdl_parser's own CMake config drags in the ROS build system, so the library and header
# are found directly. Defines the target tpf::kdl_peer.
find_package(orocos_kdl REQUIRED)
find_library(TPF_KDL_PARSER_LIBRARY kdl_parser REQUIRED)
find_path(TPF_KDL_PARSER_INCLUDE_DIR kdl_parser/kdl_parser.hpp REQUIRED)
add_library(tpf_kdl_peer INTERFACE)
target_include_directories(tpf_kdl_peer SYSTEM INTERFACE ${orocos_kdl_INCLUDE_DIRS}
                                                         ${TPF_KDL_PARSER_INCLUDE_DIR})
target_link_libraries(tpf_kdl_peer INTERFACE ${TPF_KDL_PARSER_LIBRARY} ${orocos_kdl_LIBRARIES})
add_library(tpf::kdl_peer ALIAS tpf_kdl_peer)
