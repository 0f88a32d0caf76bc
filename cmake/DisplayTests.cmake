# Debian's VTK opens an X connection even for off-screen render windows. Test programs that
# render through VTK run under `xvfb-run -a` (a private virtual display per test) when xvfb-run
# is installed; without it they use the caller's $DISPLAY. -noreset: Xvfb would otherwise reset
# (refusing connections meanwhile) whenever its last client disconnects, between windows.
find_program(MFADVR_XVFB_RUN xvfb-run)

# Call before gtest_discover_tests()/add_test() for `target`: both the test discovery and every
# test run go through the emulator.
function(mfadvr_run_under_display target)
  if(MFADVR_XVFB_RUN)
    set_property(TARGET ${target} PROPERTY CROSSCOMPILING_EMULATOR
                 "${MFADVR_XVFB_RUN};-a;-s;-screen 0 1280x1024x24 -noreset")
  endif()
endfunction()
