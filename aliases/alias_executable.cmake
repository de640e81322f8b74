# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
#
# alias_executable(name module function): install lib/<package>/<name>, a script that runs
# <module>.<function>() of amr_description with the Python the set-up built it with
# (Python3_EXECUTABLE), so that `ros2 run <package> <name>` works under upstream's names.

function(alias_executable name module function)
  file(WRITE "${CMAKE_CURRENT_BINARY_DIR}/${name}"
    "#!${Python3_EXECUTABLE}\n"
    "# ${PROJECT_NAME}'s ${name}, implemented by amr_description (${module})\n"
    "import sys\n"
    "from ${module} import ${function}\n"
    "sys.exit(${function}())\n")
  file(CHMOD "${CMAKE_CURRENT_BINARY_DIR}/${name}" PERMISSIONS OWNER_READ OWNER_WRITE
    OWNER_EXECUTE GROUP_READ GROUP_EXECUTE WORLD_READ WORLD_EXECUTE)
  install(PROGRAMS "${CMAKE_CURRENT_BINARY_DIR}/${name}" DESTINATION lib/${PROJECT_NAME})
endfunction()
