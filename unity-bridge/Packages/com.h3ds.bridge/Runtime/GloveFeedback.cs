// Plays a haptic profile on a bHaptics TactGlove through SDK2 (PlayMotors: six motor intensities,
// thumb..little tip then wrist, no authored patterns needed) and tints the virtual glove: while an
// object is held its colour transition runs (black -> blue when cooling, black -> white for light).
using System.Collections;
using Bhaptics.SDK2;
using H3ds.Bridge.Protocol;
using UnityEngine;

namespace H3ds.Bridge
{
    public class GloveFeedback : MonoBehaviour
    {
        [Tooltip("Renderers of the left and right glove/hand models to tint.")]
        [SerializeField] Renderer leftGlove;
        [SerializeField] Renderer rightGlove;

        readonly double[][] _colour = { new double[] { 0, 0, 0 }, new double[] { 0, 0, 0 } };
        readonly ColourTransition[] _holding = new ColourTransition[2];
        readonly float[] _heldSince = new float[2];

        static int Side(string hand) { return hand == "left" ? 0 : 1; }

        public static bool GloveConnected(string hand)
        {
            return BhapticsLibrary.IsConnect(hand == "left" ? PositionType.GloveL : PositionType.GloveR);
        }

        public double[] CurrentColour(string hand) { return _colour[Side(hand)]; }
        public double HeldMs(string hand) { return _holding[Side(hand)] == null ? 0 : (Time.time - _heldSince[Side(hand)]) * 1000.0; }

        /// <summary>Plays the pattern for this kind and updates the tint; returns the tint after it.</summary>
        public double[] Apply(string kind, string hand, HapticProfile profile)
        {
            int side = Side(hand);
            var pattern = GloveRules.PatternFor(kind, profile);
            if (pattern != null) StartCoroutine(Play(hand, pattern));
            var colour = GloveRules.ColourAfter(kind, profile, HeldMs(hand), _colour[side]);
            if (kind == "select" && profile != null) { _holding[side] = profile.Colour; _heldSince[side] = Time.time; }
            if (kind == "unselect") _holding[side] = null;
            SetColour(side, colour);
            return colour;
        }

        IEnumerator Play(string hand, MotorPattern pattern)
        {
            int position = (int)(hand == "left" ? PositionType.GloveL : PositionType.GloveR);
            for (int i = 0; i < pattern.Pulses; i++)
            {
                BhapticsLibrary.PlayMotors(position, (int[])pattern.Intensities.Clone(), pattern.DurationMs);
                yield return new WaitForSeconds((pattern.DurationMs + pattern.GapMs) / 1000f);
            }
        }

        void Update()
        {
            for (int side = 0; side < 2; side++)
                if (_holding[side] != null) SetColour(side, _holding[side].At((Time.time - _heldSince[side]) * 1000.0));
        }

        void SetColour(int side, double[] c)
        {
            _colour[side] = c;
            var r = side == 0 ? leftGlove : rightGlove;
            if (r != null) r.material.color = new Color((float)c[0], (float)c[1], (float)c[2]);
        }
    }
}
