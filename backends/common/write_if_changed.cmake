# write_if_changed(PATH CONTENT): writes CONTENT to PATH only when it differs
# from what PATH holds, so regenerating an unchanged file does not touch its
# timestamp and rebuild what depends on it. Included by the -P scripts here.
function(write_if_changed path content)
  if(EXISTS "${path}")
    file(READ "${path}" old)
    if(old STREQUAL content)
      return()
    endif()
  endif()
  file(WRITE "${path}" "${content}")
endfunction()
