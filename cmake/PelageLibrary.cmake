# pelage_add_library(SOURCES <files...> [PUBLIC_DEPS <targets...>]
#                    [PRIVATE_DEPS <targets...>])
#
# One library per source folder: the folder sim/mesh is the target pelage_sim_mesh
# (alias pelage::sim::mesh). Dependencies name the folders a folder may use, so an
# include that points back up the chain (renderer -> shader -> pattern -> sim) fails to
# link.
# A folder with no sources (headers only) is an INTERFACE library.
function(pelage_add_library)
    cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
    file(RELATIVE_PATH _rel ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR})
    string(REPLACE "/" "_" _name "pelage_${_rel}")
    string(REPLACE "/" "::" _alias "pelage::${_rel}")
    if(ARG_SOURCES)
        add_library(${_name} STATIC ${ARG_SOURCES})
        target_include_directories(${_name} PUBLIC ${PROJECT_SOURCE_DIR})
        target_link_libraries(${_name} PUBLIC ${ARG_PUBLIC_DEPS}
                                       PRIVATE ${ARG_PRIVATE_DEPS})
    else()
        add_library(${_name} INTERFACE)
        target_include_directories(${_name} INTERFACE ${PROJECT_SOURCE_DIR})
        target_link_libraries(${_name} INTERFACE ${ARG_PUBLIC_DEPS})
    endif()
    add_library(${_alias} ALIAS ${_name})
    set(PELAGE_LIBRARY ${_name} PARENT_SCOPE)
endfunction()
