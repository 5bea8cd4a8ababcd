// The scene component that ties it together: pairs with the studio (token typed in or set from the
// headset's UI), receives a scene_push, builds the house with AI2-THOR's CreateHouse, puts the XR rig
// at the VR start pose, makes the objects touchable, runs the robot plan step by step reporting each
// result, and turns hand interactions into haptics, glove tint and glove_event messages. Messages are
// kept until the studio acks them and resent after a reconnect (HeadsetSession / Outbox).
using System;
using System.Collections;
using System.Collections.Generic;
using System.Diagnostics;
using H3ds.Bridge.Protocol;
using UnityEngine;

namespace H3ds.Bridge
{
    public class HeadsetBridge : MonoBehaviour, IHeadsetHandler
    {
        [Header("Studio")]
        [Tooltip("ws://<studio host>:<API port>/headset, as the studio's Headset tab shows it.")]
        [SerializeField] string studioUrl = "ws://192.168.0.10:8081/headset";
        [Tooltip("The 6-digit token the studio shows (can also be set at run time with Pair).")]
        [SerializeField] string pairingToken = "";

        [Header("Scene")]
        [Tooltip("A component implementing IThorAgent (the ThorAgentAdapter sample).")]
        [SerializeField] MonoBehaviour thorAgent;
        [SerializeField] XrRigPlacer rigPlacer;
        [SerializeField] InteractionBinder interactions;
        [SerializeField] GloveFeedback gloves;
        [Tooltip("Seconds between robot steps, so the person can follow the robot.")]
        [SerializeField] float stepPause = 0.5f;

        public const string SupportedHouseSchema = "1.0.0";

        HeadsetSession _session;
        IThorAgent _thor;
        ScenePush _scene;
        float _sceneLoadedAt;
        readonly Dictionary<string, SpawnedObject> _objects = new Dictionary<string, SpawnedObject>();

        public SessionState State { get { return _session == null ? SessionState.Idle : _session.State; } }
        /// <summary>What went wrong last (shown in the headset's status panel).</summary>
        public string Status { get; private set; }

        static double Now() { return (DateTime.UtcNow - new DateTime(1970, 1, 1, 0, 0, 0, DateTimeKind.Utc)).TotalSeconds; }

        void Start()
        {
            _thor = thorAgent as IThorAgent;
            if (_thor == null) Status = "thorAgent must be a component implementing IThorAgent (see the ThorAdapter sample)";
            var hello = new Hello
            {
                Role = "headset", Device = SystemInfo.deviceModel, AppVersion = Application.version,
                Capabilities = new List<string> { "ai2thor", "hand-tracking", "bhaptics" },
                Gloves = new GloveState { Left = GloveFeedback.GloveConnected("left"), Right = GloveFeedback.GloveConnected("right") },
            };
            _session = new HeadsetSession(new Uri(studioUrl), Guid.NewGuid().ToString(), hello, this, Now);
            if (interactions != null) interactions.Interaction += OnInteraction;
            if (!string.IsNullOrEmpty(pairingToken)) Pair(pairingToken);
        }

        /// <summary>Pairs with the token shown in the studio.</summary>
        public void Pair(string token) { _session.PairWith(token.Trim()); }

        /// <summary>The person's verdict on the scene (from the headset's UI).</summary>
        public void Decide(bool accept, string comment)
        {
            if (_scene == null) return;
            _session.Send(new UserDecision { Push = _scene.Push, Decision = accept ? "accept" : "reject", Comment = comment });
        }

        void Update() { if (_session != null) _session.Poll(); }

        void OnDestroy() { if (_session != null) _session.End("headset app closed"); }

        public void OnPaired(Paired paired) { Status = "paired with " + paired.Studio; }
        public void OnStudioError(ErrorMessage error) { Status = "studio: " + error.Code + ": " + error.Message; }
        public void OnDisconnected(string reason) { Status = "disconnected (" + reason + "); events are kept and resent"; }

        public void OnScenePush(ScenePush push)
        {
            StopAllCoroutines();
            StartCoroutine(LoadAndRun(push));
        }

        IEnumerator LoadAndRun(ScenePush push)
        {
            _scene = push;
            _objects.Clear();
            if (interactions != null) interactions.Clear();
            string problem = _thor == null ? "the headset app is not wired to AI2-THOR (HeadsetBridge.thorAgent)" : CheckHouse(push);
            if (problem != null) { _session.Send(new SceneFailed { Push = push.Push, Reason = problem }); yield break; }

            var watch = Stopwatch.StartNew();
            var created = new ThorResult();
            yield return _thor.Run(new Dictionary<string, object> { { "action", "CreateHouse" }, { "house", push.House } }, created);
            if (!created.Success)
            {
                _session.Send(new SceneFailed { Push = push.Push, Reason = "CreateHouse failed: " + (created.Error ?? "no message") });
                yield break;
            }
            foreach (var o in _thor.SpawnedObjects()) _objects[o.ObjectId] = o;
            if (rigPlacer != null) rigPlacer.Place(push.VrBest);
            if (interactions != null) interactions.Bind(_objects.Values);
            _sceneLoadedAt = Time.time;
            _session.Send(new SceneLoaded { Push = push.Push, LoadMs = watch.Elapsed.TotalMilliseconds, Objects = _objects.Count });

            if (push.Plan == null) yield break;
            var steps = push.Plan.Steps;
            for (int i = 0; i < steps.Count; i++)
            {
                var result = new ThorResult();
                yield return _thor.Run(steps[i].Action, result);
                _session.Send(new PlanStepResult
                {
                    Push = push.Push, Index = i, Of = steps.Count, Action = steps[i].ActionName, Ok = result.Success,
                    Message = result.Success ? steps[i].Description : "failed: " + (result.Error ?? "no message"),
                });
                if (!result.Success) yield break;  // later steps assume this one happened
                yield return new WaitForSeconds(stepPause);
            }
        }

        /// <summary>What CreateHouse would refuse, said before trying: AI2-THOR accepts only schema 1.0.0.</summary>
        static string CheckHouse(ScenePush push)
        {
            if (push.House == null) return "the scene has no house";
            object meta;
            push.House.TryGetValue("metadata", out meta);
            var metadata = meta as Dictionary<string, object>;
            object schema = null;
            if (metadata != null) metadata.TryGetValue("schema", out schema);
            if (!(schema is string) || (string)schema != SupportedHouseSchema)
                return "house metadata.schema is '" + (schema ?? "missing") + "'; AI2-THOR's CreateHouse accepts only '" + SupportedHouseSchema + "'";
            return null;
        }

        void OnInteraction(string kind, SpawnedObject obj, string hand, List<string> fingers)
        {
            if (_scene == null) return;
            HapticProfile profile;
            _scene.HapticProfiles.TryGetValue(obj.ObjectId, out profile);
            double[] colour = gloves != null ? gloves.Apply(kind, hand, profile) : GloveRules.Neutral;
            _session.Send(GloveRules.Event(_scene.Push, Time.time - _sceneLoadedAt, obj.ObjectId, obj.ObjectType, kind, hand,
                fingers, profile, colour));
        }
    }
}
