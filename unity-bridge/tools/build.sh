#!/usr/bin/env bash
# Compile-check the Unity package with Debian's mono-mcs (C# 7.2) against the project's STUB assemblies
# of UnityEngine, the Meta XR Interaction SDK, bHaptics SDK2 and AI2-THOR (unity-bridge/stubs/), and build
# the protocol check program (tools/ProtocolCheck.cs). Usage: build.sh OUTDIR
# Passing proves the scripts agree with our stubs, not with the real SDKs.
set -euo pipefail
out=${1:?usage: build.sh OUTDIR}
here=$(cd "$(dirname "$0")/.." && pwd)
pkg=$here/Packages/com.h3ds.bridge
stubs=$here/stubs
command -v mcs >/dev/null || { echo "mcs is missing: install Debian's mono-mcs (apt-get install mono-mcs)" >&2; exit 127; }
mkdir -p "$out"
MCS="mcs -langversion:7.2 -warnaserror+ -nologo"
$MCS -target:library -out:"$out/UnityEngine.dll" "$stubs/UnityEngine.cs"
$MCS -target:library -r:"$out/UnityEngine.dll" -out:"$out/Oculus.Interaction.dll" "$stubs/OculusInteraction.cs"
$MCS -target:library -out:"$out/Bhaptics.SDK2.dll" "$stubs/Bhaptics.cs"
# The protocol layer has no engine references (its asmdef says noEngineReferences): compiled alone.
$MCS -target:library -out:"$out/H3ds.Bridge.Protocol.dll" "$pkg"/Runtime/Protocol/*.cs
$MCS -target:library -r:"$out/UnityEngine.dll" -r:"$out/Oculus.Interaction.dll" -r:"$out/Bhaptics.SDK2.dll" \
  -r:"$out/H3ds.Bridge.Protocol.dll" -out:"$out/H3ds.Bridge.dll" "$pkg"/Runtime/*.cs
# AI2-THOR's scripts (Assembly-CSharp) with the sample adapter that a developer copies into them.
$MCS -target:library -r:"$out/UnityEngine.dll" -r:"$out/H3ds.Bridge.dll" -r:"$out/H3ds.Bridge.Protocol.dll" \
  -out:"$out/Assembly-CSharp.dll" "$stubs/Ai2Thor.cs" "$pkg/Samples~/ThorAdapter/ThorAgentAdapter.cs"
$MCS -target:exe -r:"$out/H3ds.Bridge.Protocol.dll" -out:"$out/ProtocolCheck.exe" "$here/tools/ProtocolCheck.cs"
echo "built into $out"
