// STUB, not the bHaptics SDK2 Unity plugin: BhapticsLibrary.PlayMotors and PositionType as the SDK2
// documents them (six motors per TactGlove). Agreement with this file proves agreement with this file only.
namespace Bhaptics.SDK2
{
    public enum PositionType
    {
        Vest = 0, ForearmL = 1, ForearmR = 2, Head = 3, HandL = 4, HandR = 5, FootL = 6, FootR = 7,
        GloveL = 8, GloveR = 9,
    }

    public static class BhapticsLibrary
    {
        public static int PlayMotors(int position, int[] motors, int durationMillis) { return 0; }
        public static bool IsConnect(PositionType type) { return false; }
        public static void StopAll() { }
    }
}
