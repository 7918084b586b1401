#!/usr/bin/env bash
# System packages for the editor's tests. Installs only what is missing (apt, as root or with
# sudo).
# - Required: egui_kittest renders with wgpu on Mesa's software Vulkan driver (lavapipe):
#   libvulkan1 mesa-vulkan-drivers.
# - Optional: the smoke tests that open the real editor window under a virtual X server and
#   take screenshots: xvfb xauth x11-apps (xwd) netpbm (xwdtopnm, pnmtopng); the one that
#   presses keys and closes the window as a window manager would also needs xdotool (focus,
#   keys, clicks, window title) and python3-xlib (the WM_DELETE_WINDOW client message, sent
#   with the system's /usr/bin/python3). If they cannot be installed, those tests say so and
#   are skipped.
set -euo pipefail
missing() {
    for p in "$@"; do
        dpkg -s "$p" >/dev/null 2>&1 || echo "$p"
    done
}
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
updated=""
install() {
    if [ -z "$updated" ]; then
        $sudo apt-get update -qq && updated=1
    fi
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "$@"
}
mapfile -t need < <(missing libvulkan1 mesa-vulkan-drivers)
if [ ${#need[@]} -gt 0 ]; then
    echo "installing ${need[*]} (headless rendering for the editor's tests)"
    install "${need[@]}"
fi
mapfile -t want < <(missing xvfb xauth x11-apps netpbm xdotool python3-xlib)
if [ ${#want[@]} -gt 0 ]; then
    echo "installing ${want[*]} (the editor's real-window smoke tests)"
    install "${want[@]}" || echo "warning: could not install ${want[*]}; the Xvfb smoke tests will be skipped"
fi
