// scene_push (studio -> headset): the house JSON kept verbatim for CreateHouse, the VR start pose,
// the haptic profiles (one per house object id) and the robot plan (AI2-THOR action dicts).
using System.Collections.Generic;

namespace H3ds.Bridge.Protocol
{
    public sealed class AgentPose
    {
        public double X, Z, Rotation, Horizon = 30.0;

        public static AgentPose FromBody(Dictionary<string, object> b)
        {
            var p = new AgentPose { X = Fields.Double(b, "x"), Z = Fields.Double(b, "z"), Rotation = Fields.Double(b, "rotation") };
            if (Fields.Has(b, "horizon")) p.Horizon = Fields.Double(b, "horizon");
            return p;
        }
    }

    /// <summary>One PlayMotors call: six intensities (thumb, index, middle, ring, little, wrist), pulses.</summary>
    public sealed class MotorPattern
    {
        public int[] Intensities = new int[6];
        public int DurationMs, Pulses = 1, GapMs;

        public int Peak
        {
            get { int m = 0; foreach (var i in Intensities) if (i > m) m = i; return m; }
        }

        public static MotorPattern FromBody(Dictionary<string, object> b)
        {
            var list = Fields.List(b, "intensities");
            if (list.Count != 6) throw new ProtocolException("field 'intensities' must hold 6 motors, not " + list.Count);
            var m = new MotorPattern { DurationMs = (int)Fields.Long(b, "duration_ms") };
            for (int i = 0; i < 6; i++) m.Intensities[i] = (int)Fields.AsDouble(list[i], "intensities[" + i + "]");
            if (Fields.Has(b, "pulses")) m.Pulses = (int)Fields.Long(b, "pulses");
            if (Fields.Has(b, "gap_ms")) m.GapMs = (int)Fields.Long(b, "gap_ms");
            return m;
        }
    }

    /// <summary>The glove tint while holding the object: start -> end (linear RGB) over DurationMs.</summary>
    public sealed class ColourTransition
    {
        public double[] Start = new double[3], End = new double[3];
        public int DurationMs;
        public string Name;

        /// <summary>The colour after holding for elapsedMs (clamped to the transition).</summary>
        public double[] At(double elapsedMs)
        {
            double f = DurationMs <= 0 ? 1.0 : elapsedMs / DurationMs;
            if (f < 0) f = 0;
            if (f > 1) f = 1;
            var c = new double[3];
            for (int i = 0; i < 3; i++) c[i] = Start[i] + (End[i] - Start[i]) * f;
            return c;
        }

        static double[] Rgb(Dictionary<string, object> b, string key)
        {
            var l = Fields.List(b, key);
            if (l.Count != 3) throw new ProtocolException("field '" + key + "' must be [r, g, b]");
            return new[] { Fields.AsDouble(l[0], key), Fields.AsDouble(l[1], key), Fields.AsDouble(l[2], key) };
        }

        public static ColourTransition FromBody(Dictionary<string, object> b)
        {
            return new ColourTransition
            {
                Start = Rgb(b, "start"), End = Rgb(b, "end"),
                DurationMs = (int)Fields.Long(b, "duration_ms"), Name = Fields.String(b, "name"),
            };
        }
    }

    public sealed class HapticProfile
    {
        public string ObjectId, SceneObjectId, ObjectType, HapticClass, Why;
        public MotorPattern Touch, Grasp;
        public ColourTransition Colour;

        public static HapticProfile FromBody(Dictionary<string, object> b)
        {
            return new HapticProfile
            {
                ObjectId = Fields.String(b, "object_id"),
                SceneObjectId = Fields.String(b, "scene_object_id"),
                ObjectType = Fields.String(b, "object_type"),
                HapticClass = Fields.String(b, "haptic_class"),
                Touch = MotorPattern.FromBody(Fields.Dict(b, "touch")),
                Grasp = MotorPattern.FromBody(Fields.Dict(b, "grasp")),
                Colour = ColourTransition.FromBody(Fields.Dict(b, "colour")),
                Why = Fields.OptString(b, "why"),
            };
        }
    }

    public sealed class PlanStep
    {
        public long Index;
        /// <summary>The AI2-THOR action exactly as controller.step(**action) takes it ("action", "objectId", ...).</summary>
        public Dictionary<string, object> Action;
        public string Description, Target;

        public string ActionName { get { return Action.ContainsKey("action") ? Action["action"] as string : null; } }

        public static PlanStep FromBody(Dictionary<string, object> b)
        {
            var s = new PlanStep
            {
                Index = Fields.Long(b, "index"), Action = Fields.Dict(b, "action"),
                Description = Fields.String(b, "description"), Target = Fields.OptString(b, "target"),
            };
            if (s.ActionName == null) throw new ProtocolException("plan step " + s.Index + " has no 'action' name");
            return s;
        }
    }

    public sealed class RobotPlan
    {
        public string TaskType, Instruction;
        public List<PlanStep> Steps = new List<PlanStep>();
        public List<string> Problems = new List<string>();

        public static RobotPlan FromBody(Dictionary<string, object> b)
        {
            var p = new RobotPlan { TaskType = Fields.String(b, "task_type"), Instruction = Fields.String(b, "instruction") };
            foreach (var s in Fields.List(b, "steps"))
            {
                var d = s as Dictionary<string, object>;
                if (d == null) throw new ProtocolException("a plan step must be an object");
                p.Steps.Add(PlanStep.FromBody(d));
            }
            if (Fields.Has(b, "problems")) foreach (var x in Fields.List(b, "problems")) p.Problems.Add(x as string);
            return p;
        }
    }

    public sealed class ScenePush
    {
        public string Push, Name, Instruction;
        public long SceneId, Version;
        public Dictionary<string, object> House;
        public AgentPose VrBest;  // null when no valid pose was found
        public List<AgentPose> VrAlternatives = new List<AgentPose>();
        public Dictionary<string, HapticProfile> HapticProfiles = new Dictionary<string, HapticProfile>();
        public RobotPlan Plan;

        /// <summary>The house JSON as sent (the exact text CreateHouse gets).</summary>
        public string HouseJson { get { return Json.Write(House); } }

        public static ScenePush FromBody(Dictionary<string, object> b)
        {
            var p = new ScenePush
            {
                Push = Fields.String(b, "push"),
                SceneId = Fields.Has(b, "scene_id") ? Fields.Long(b, "scene_id") : 0,
                Version = Fields.Has(b, "version") ? Fields.Long(b, "version") : 0,
                Name = Fields.OptString(b, "name"),
                Instruction = Fields.OptString(b, "instruction"),
                House = Fields.Dict(b, "house"),
            };
            if (Fields.Has(b, "vr_start_pose"))
            {
                var vr = Fields.Dict(b, "vr_start_pose");
                if (Fields.Has(vr, "best")) p.VrBest = AgentPose.FromBody(Fields.Dict(vr, "best"));
                if (Fields.Has(vr, "alternatives"))
                    foreach (var a in Fields.List(vr, "alternatives"))
                        p.VrAlternatives.Add(AgentPose.FromBody(Fields.Dict((Dictionary<string, object>)a, "pose")));
            }
            if (Fields.Has(b, "haptic_profiles"))
                foreach (var h in Fields.List(b, "haptic_profiles"))
                {
                    var profile = HapticProfile.FromBody((Dictionary<string, object>)h);
                    p.HapticProfiles[profile.ObjectId] = profile;
                }
            if (Fields.Has(b, "robot_plan")) p.Plan = RobotPlan.FromBody(Fields.Dict(b, "robot_plan"));
            return p;
        }
    }
}
