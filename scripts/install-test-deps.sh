#!/usr/bin/env bash
# System packages for the editor's UI tests: egui_kittest renders with wgpu on Mesa's
# software Vulkan driver (lavapipe). Installs only what is missing (apt, as root or with sudo).
set -euo pipefail
need=()
for p in libvulkan1 mesa-vulkan-drivers; do
    dpkg -s "$p" >/dev/null 2>&1 || need+=("$p")
done
if [ ${#need[@]} -eq 0 ]; then
    exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "installing ${need[*]} (headless rendering for the editor's tests)"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${need[@]}"
