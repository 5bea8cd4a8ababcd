// What a glove does when a hand meets an object, as pure logic (tested under mono): which motor
// pattern plays (touch on hover, grasp on select, nothing on unhover / unselect), the glove's tint
// (the profile's colour transition runs while the object is held: black -> blue when cooling,
// black -> white for light), and the glove event that reports it.
using System.Collections.Generic;

namespace H3ds.Bridge.Protocol
{
    public static class GloveRules
    {
        public static readonly double[] Neutral = { 0, 0, 0 };

        /// <summary>The pattern to play for an interaction kind, or null for none.</summary>
        public static MotorPattern PatternFor(string kind, HapticProfile profile)
        {
            if (profile == null) return null;
            if (kind == "hover") return profile.Touch;
            if (kind == "select") return profile.Grasp;
            return null;
        }

        /// <summary>The glove tint after the event; heldMs is how long the object has been held.</summary>
        public static double[] ColourAfter(string kind, HapticProfile profile, double heldMs, double[] current)
        {
            if (profile == null) return current ?? Neutral;
            if (kind == "select") return profile.Colour.At(0);
            if (kind == "unselect") return profile.Colour.At(heldMs);
            return current ?? Neutral;
        }

        /// <summary>Finger names as the protocol spells them, from the Meta SDK's finger flags (bit 0 thumb ... bit 4 pinky).</summary>
        public static List<string> FingerNames(int handFingerFlags)
        {
            var names = new List<string>();
            string[] order = { "thumb", "index", "middle", "ring", "little" };
            for (int i = 0; i < order.Length; i++) if ((handFingerFlags & (1 << i)) != 0) names.Add(order[i]);
            return names;
        }

        public static GloveEvent Event(string push, double t, string objectId, string objectType, string kind, string hand,
            List<string> fingers, HapticProfile profile, double[] colour)
        {
            var pattern = PatternFor(kind, profile);
            return new GloveEvent
            {
                Push = push, T = t < 0 ? 0 : t, ObjectId = objectId, ObjectType = objectType, Kind = kind, Hand = hand,
                Fingers = fingers ?? new List<string>(),
                HapticClass = profile != null ? profile.HapticClass : "normal",
                Intensity = pattern != null ? pattern.Peak : 0,
                GloveColour = new[] { Clamp(colour[0]), Clamp(colour[1]), Clamp(colour[2]) },
            };
        }

        static double Clamp(double v) { return v < 0 ? 0 : v > 1 ? 1 : v; }
    }
}
