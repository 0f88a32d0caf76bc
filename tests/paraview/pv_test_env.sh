# Sourced by the ParaView test drivers: exits 77 (skipped) unless every tool named in
# PV_TOOLS is installed, then sets what mpiexec and pvbatch need here.
for tool in $PV_TOOLS; do
  if ! command -v "$tool" >/dev/null; then
    echo "skipped: $tool is not installed"
    exit 77
  fi
done
# Open MPI refuses to start as root unless told; four ranks may outnumber the cores.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export PYTHONPATH="$here${PYTHONPATH:+:$PYTHONPATH}"
# A 24-bit screen, and no X display test (pvbatch/pvserver --disable-xdisplay-test): ParaView's
# per-rank probe of the display now and then fails when several ranks start at once on one
# Xvfb, and the view then waits for remote rendering that it has disabled. -noreset: Xvfb
# otherwise resets (refusing connections meanwhile) whenever its last client disconnects.
screen=(-s "-screen 0 1280x1024x24 -noreset")
