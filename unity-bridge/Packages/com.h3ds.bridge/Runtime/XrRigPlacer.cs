// Puts the XR rig where the studio says the person should stand (the VR start pose): AI2-THOR's
// x, z on the floor (y = 0 in a ProcTHOR house), facing `rotation` degrees about the vertical axis.
using H3ds.Bridge.Protocol;
using UnityEngine;

namespace H3ds.Bridge
{
    public class XrRigPlacer : MonoBehaviour
    {
        [Tooltip("The XR rig's root (OVRCameraRig or the Interaction SDK's rig), moved as a whole.")]
        [SerializeField] Transform rigRoot;

        public void Place(AgentPose pose)
        {
            if (pose == null || rigRoot == null) return;
            rigRoot.position = new Vector3((float)pose.X, 0f, (float)pose.Z);
            rigRoot.rotation = Quaternion.Euler(0f, (float)pose.Rotation, 0f);
        }
    }
}
