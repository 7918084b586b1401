#!/usr/bin/env bash
# System packages for the editor's tests. Installs only what is missing (apt, as root or with
# sudo).
# - Required: egui_kittest renders with wgpu on Mesa's software Vulkan driver (lavapipe):
#   libvulkan1 mesa-vulkan-drivers.
# - Optional: the smoke test that opens the real editor window under a virtual X server and
#   takes a screenshot: xvfb xauth x11-apps (xwd) netpbm (xwdtopnm, pnmtopng). If they cannot
#   be installed, that one test says so and is skipped.
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
mapfile -t want < <(missing xvfb xauth x11-apps netpbm)
if [ ${#want[@]} -gt 0 ]; then
    echo "installing ${want[*]} (the editor's real-window smoke test)"
    install "${want[@]}" || echo "warning: could not install ${want[*]}; the Xvfb smoke test will be skipped"
fi
