# Slides, gallery and the main job's Python tools (see slides/README.md).
#   slides                          builds every slides/NN_*.md into test-out/slides and opens each
#                                   in headless Chromium: no KaTeX error, every image loads
#                                   (images are the e2e tests' lesson outputs in test-out/lessonNN)
#   slides_checker_catches_errors   the checker must reject tests/slides/fixtures/99_broken.md
#   gallery_index                   index.html over test-out; every local link and image resolves
#   gallery_tools                   unit tests of tools/gallery (index, output checks) and check_outputs.py
# A missing Node.js, node_modules (npm ci) or Chromium fails these tests with a pointer to
# tools/install-deps; they never pass by skipping.
set(ILLUM_TEST_OUT ${CMAKE_BINARY_DIR}/test-out)

add_test(NAME slides
         COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/slides/run_slide_test.py decks
                 --out ${ILLUM_TEST_OUT})
set_tests_properties(slides PROPERTIES FIXTURES_REQUIRED lesson_outputs LABELS slides TIMEOUT 900)

add_test(NAME slides_checker_catches_errors
         COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/slides/run_slide_test.py expect-failure
                 --out ${ILLUM_TEST_OUT}/slides-fixture)
set_tests_properties(slides_checker_catches_errors PROPERTIES LABELS slides TIMEOUT 300)

add_test(NAME gallery_index
         COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/main_job.py --only index --check-links
                 --source ${PROJECT_SOURCE_DIR} --out ${ILLUM_TEST_OUT})
# After `slides` when both run, so the index sees the built decks; it does not need them to pass.
set_tests_properties(gallery_index PROPERTIES FIXTURES_REQUIRED lesson_outputs DEPENDS slides LABELS slides)

add_test(NAME gallery_tools
         COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/tools/test_gallery.py)
set_tests_properties(gallery_tools PROPERTIES LABELS slides TIMEOUT 300)

# The texts as pages (tools/gallery/render_texts.mjs, the main job's step "texts"):
#   text_pages                        renders every text into test-out/pages and opens lesson 06's,
#                                     lesson 09's, the errata and an exercise in headless Chromium:
#                                     formulas render in KaTeX's fonts, images load, links resolve
#   text_pages_checker_catches_errors the checker must name a KaTeX error, a missing image and a
#                                     link to a missing anchor planted in a page
add_test(NAME text_pages
         COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/texts/run_page_test.py pages
                 --out ${ILLUM_TEST_OUT})
set_tests_properties(text_pages PROPERTIES FIXTURES_REQUIRED lesson_outputs LABELS slides TIMEOUT 600
                                           ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
add_test(NAME text_pages_checker_catches_errors
         COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/texts/run_page_test.py expect-failure
                 --out ${ILLUM_TEST_OUT}/pages-fixture)
set_tests_properties(text_pages_checker_catches_errors PROPERTIES LABELS slides TIMEOUT 300
                                                                  ENVIRONMENT PYTHONDONTWRITEBYTECODE=1)
