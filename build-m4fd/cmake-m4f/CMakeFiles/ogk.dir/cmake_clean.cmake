file(REMOVE_RECURSE
  "libogk.a"
  "libogk.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang C)
  include(CMakeFiles/ogk.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
