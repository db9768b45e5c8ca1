# The pages' budget in words (CONTRIBUTING.md, "Pages and their budget"), counted as wc -w counts
# them (runs of characters that are not white space). Run as a test:
# cmake -DSOURCE=<root> -P tests/e2e/docs_budget.cmake; it fails naming each page over its budget.
set(page_budget 4000)    # every page of docs/
set(readme_budget 1500)  # README.md
set(quick_start_budget 200)  # README.md's "Quick start" section
# Pages still being split, with the budget they keep until then.
set(over_budget_pages "")

function(count_words text out)
  # A CMake list is not split inside square brackets ("[0," and "1]" would count once): make them
  # round first, which leaves the runs of non-space characters as they are.
  string(REPLACE "[" "(" text "${text}")
  string(REPLACE "]" ")" text "${text}")
  string(REGEX MATCHALL "[^ \t\r\n]+" words "${text}")
  list(LENGTH words n)
  set(${out} ${n} PARENT_SCOPE)
endfunction()

set(problems "")
file(GLOB pages RELATIVE ${SOURCE} ${SOURCE}/docs/*.md)
foreach(page IN LISTS pages)
  file(READ ${SOURCE}/${page} text)
  string(REPLACE ";" " " text "${text}")
  count_words("${text}" n)
  set(budget ${page_budget})
  foreach(entry IN LISTS over_budget_pages)
    if(entry MATCHES "^${page}=([0-9]+)$")
      set(budget ${CMAKE_MATCH_1})
    endif()
  endforeach()
  if(n GREATER budget)
    string(APPEND problems "${page}: ${n} words, the budget is ${budget}\n")
  endif()
endforeach()
file(READ ${SOURCE}/README.md readme)
string(REPLACE ";" " " readme "${readme}")
count_words("${readme}" n)
if(n GREATER readme_budget)
  string(APPEND problems "README.md: ${n} words, the budget is ${readme_budget}\n")
endif()
string(FIND "${readme}" "\n## Quick start\n" start)
if(start EQUAL -1)
  string(APPEND problems "README.md: no \"## Quick start\" section\n")
else()
  math(EXPR start "${start} + 16")
  string(SUBSTRING "${readme}" ${start} -1 rest)
  string(FIND "${rest}" "\n## " end)
  string(SUBSTRING "${rest}" 0 ${end} quick_start)
  count_words("${quick_start}" n)
  if(n GREATER quick_start_budget)
    string(APPEND problems "README.md, Quick start: ${n} words, the budget is ${quick_start_budget}\n")
  endif()
endif()
if(problems)
  message(FATAL_ERROR "pages over their budget (CONTRIBUTING.md, \"Pages and their budget\"):\n${problems}")
endif()
message(STATUS "docs_budget: every page within its budget")
