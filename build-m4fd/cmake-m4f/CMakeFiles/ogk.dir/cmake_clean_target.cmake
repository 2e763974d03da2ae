file(REMOVE_RECURSE
  "libogk.a"
)
